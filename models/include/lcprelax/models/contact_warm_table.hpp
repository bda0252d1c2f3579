#pragma once
// The previous step's basis (LCP model) or active set (convex active-set model) per
// contact, keyed by the contact's identity across steps (contact_system.hpp ContactKey),
// as the codes of lcp_basis_codes.hpp: what the simulator's warm starts read.
//
// A sorted array searched by bisection. The simulator refills a second table each step
// and swaps the two, so the storage keeps its capacity and a step allocates nothing per
// contact once the tables have grown to the scene's contact count (a node-based map would
// allocate one node per contact per step; tests/simulator_step_allocation_test.cpp).
//
// Writes follow std::map's `table[key].normal = x` semantics exactly: a key written
// several times keeps, for each field, the last value written to it, and a field never
// written is 0.
#include <lcprelax/models/contact_system.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace lcprelax {

/// One contact's entry of a ContactWarmTable with its key: a table's contents as values
/// (records(), assign(); the Simulator's warm_start_state and a scene file's "warm_start").
struct ContactWarmRecord {
  ContactKey key{};
  double normal = 0.0, friction = 0.0;  ///< lcp_basis_codes.hpp: normal 0/1, friction 0..7
  /// LCP model: the basis is that of a regularized answer (a basis of M + εI, often singular
  /// in M) or the one a failed step started from; an island with such an entry runs the
  /// lcp model's step 1c first (contact_step.hpp, solve_lcp_model's warm_from_regularized).
  bool regularized = false;
};

/// Why `r` cannot be a contact's entry in a world of `bodies` bodies ("" when it can): body a
/// outside [0, bodies), body b outside [−1, bodies), static kind outside 0..2, static index
/// < −1, ordinal < 0, a normal code other than 0 or 1, a friction code not an integer in 0..7.
std::string contact_warm_record_error(const ContactWarmRecord& r, int bodies);

class ContactWarmTable {
 public:
  struct Entry {
    double normal = 0.0, friction = 0.0;
    bool regularized = false;  ///< ContactWarmRecord::regularized
  };

  /// Empties the table for refilling (capacity kept).
  void clear();
  /// Records a write of one field of `key`'s entry; find() needs finish() first.
  void set_normal(const ContactKey& key, double code) { writes_.push_back({key, writes_.size(), code, Field::normal}); }
  void set_friction(const ContactKey& key, double code) {
    writes_.push_back({key, writes_.size(), code, Field::friction});
  }
  void set_regularized(const ContactKey& key, bool regularized) {
    writes_.push_back({key, writes_.size(), regularized ? 1.0 : 0.0, Field::regularized});
  }
  /// Merges the writes into one entry per key, sorted by key (no allocation beyond the
  /// capacity that the writes already needed).
  void finish();
  /// The entry of `key`, or nullptr when the table has none (after finish()).
  const Entry* find(const ContactKey& key) const;
  /// out[i] = find(keys[i]) for every key (after finish()). Keys in increasing order (as
  /// find_contacts' contacts give them) take one merge pass, O(keys + size()); other
  /// orders a find() each.
  void find_sorted(const std::vector<ContactKey>& keys, std::vector<const Entry*>& out) const;
  /// The entries with their keys, in key order (after finish()).
  std::vector<ContactWarmRecord> records() const;
  /// Replaces the contents by `records` (clear, one write per field, finish): a key listed
  /// twice keeps its last record's fields.
  void assign(const std::vector<ContactWarmRecord>& records);
  /// Number of keys (after finish()).
  std::size_t size() const { return keys_.size(); }
  void swap(ContactWarmTable& other) noexcept {
    writes_.swap(other.writes_);
    keys_.swap(other.keys_);
    entries_.swap(other.entries_);
  }

 private:
  enum class Field : unsigned char { normal, friction, regularized };
  struct Write {
    ContactKey key;
    std::size_t order;  // position among the writes: later writes win
    double code;        // regularized: 1 or 0
    Field field;
  };
  std::vector<Write> writes_;
  std::vector<ContactKey> keys_;  // sorted, distinct
  std::vector<Entry> entries_;    // entries_[i] belongs to keys_[i]
};

}  // namespace lcprelax
