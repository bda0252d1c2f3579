#pragma once
// Values per contact of one transition, kept between evaluations: the relaxed step loss's
// proximal centres (step_loss_relaxed.hpp), or the hard loss's final Lemke basis coded per
// contact (scene_objective.cpp), in the same layout. Matched CONTACT BY CONTACT: a
// learned vertex or μ changes which contacts the speculative margin admits, how islands split and the order of their rows, so
// a centre stored per island row would fall back to 0 (the biased shift) whenever anything in
// the island changed. Each value is keyed by the contact's identity — the body pair (or body
// and static shape) and the narrow-phase feature that made it (Contact::Feature) — and, for
// γ, the friction row's rank among its contact's rows. Contacts without a stored value get
// centre 0 and are counted. Internal to the learn layer.
#include <lcprelax/learn/state_stream.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/world/world.hpp>

#include <array>
#include <utility>
#include <vector>

namespace lcprelax::learn::detail {

class ProximalCenters {
 public:
  /// The centre [λ̃n (nc); γ (nf)] of island `s` whose rows index `contacts` (the transition's
  /// contact list); returns the number of the island's contacts with no stored value.
  int lookup(const std::vector<Contact>& contacts, const ContactSystem& s, Vector& center) const;
  /// Records the island's solution `point` ([λ̃n; γ]) for the next evaluation (after commit()).
  void record(const std::vector<Contact>& contacts, const ContactSystem& s, const Vector& point);
  /// Starts an evaluation: forgets values recorded but not committed (a failed transition).
  void begin() { next_.clear(); }
  /// The recorded values become the stored ones (the previous ones are forgotten).
  void commit();
  void clear();
  bool empty() const { return stored_.empty(); }
  /// The stored values, for training checkpoints (Objective::save_state).
  void save(StateWriter& out) const;
  /// Reads what save() wrote (sorted keys); InputError through `in` otherwise.
  void load(StateReader& in);

 private:
  using Key = std::array<int, 10>;  // contact identity (9) and slot: −1 for λ̃n, j for the j-th γ
  static Key key(const Contact& c, int slot);
  double find(const Key& k, bool& found) const;
  std::vector<std::pair<Key, double>> stored_, next_;
};

}  // namespace lcprelax::learn::detail
