// Proximal centres matched contact by contact (proximal_centers.hpp).
#include "proximal_centers.hpp"

#include <algorithm>
#include <cstdint>

namespace lcprelax::learn::detail {
namespace {

// Rank of each friction row among its contact's rows.
std::vector<int> friction_slots(const ContactSystem& s) {
  std::vector<int> seen(static_cast<std::size_t>(s.num_contacts()), 0), slot(s.friction_rows.size());
  for (std::size_t f = 0; f < s.friction_rows.size(); ++f) slot[f] = seen[static_cast<std::size_t>(s.friction_rows[f])]++;
  return slot;
}

}  // namespace

ProximalCenters::Key ProximalCenters::key(const Contact& c, int slot) {
  const Contact::Feature& f = c.feature;
  return {c.body_a, c.body_b, static_cast<int>(c.static_kind), c.static_index, static_cast<int>(f.kind),
          f.face_on_a ? 1 : 0, f.edge, f.vertex, f.side, slot};
}

double ProximalCenters::find(const Key& k, bool& found) const {
  const auto it = std::lower_bound(stored_.begin(), stored_.end(), k,
                                   [](const std::pair<Key, double>& e, const Key& x) { return e.first < x; });
  found = it != stored_.end() && it->first == k;
  return found ? it->second : 0.0;
}

int ProximalCenters::lookup(const std::vector<Contact>& contacts, const ContactSystem& s, Vector& center) const {
  const Index nc = s.num_contacts(), nf = s.num_friction();
  center.setZero(nc + nf);
  std::vector<bool> cold(static_cast<std::size_t>(nc), false);
  bool found = false;
  for (Index c = 0; c < nc; ++c) {
    const Contact& con = contacts[static_cast<std::size_t>(s.contacts[static_cast<std::size_t>(c)])];
    center(c) = find(key(con, -1), found);
    if (!found) cold[static_cast<std::size_t>(c)] = true;
  }
  const std::vector<int> slot = friction_slots(s);
  for (Index f = 0; f < nf; ++f) {
    const int c = s.friction_rows[static_cast<std::size_t>(f)];
    const Contact& con = contacts[static_cast<std::size_t>(s.contacts[static_cast<std::size_t>(c)])];
    center(nc + f) = find(key(con, slot[static_cast<std::size_t>(f)]), found);
    if (!found) cold[static_cast<std::size_t>(c)] = true;
  }
  return static_cast<int>(std::count(cold.begin(), cold.end(), true));
}

void ProximalCenters::record(const std::vector<Contact>& contacts, const ContactSystem& s, const Vector& point) {
  const Index nc = s.num_contacts(), nf = s.num_friction();
  for (Index c = 0; c < nc; ++c)
    next_.emplace_back(key(contacts[static_cast<std::size_t>(s.contacts[static_cast<std::size_t>(c)])], -1), point(c));
  const std::vector<int> slot = friction_slots(s);
  for (Index f = 0; f < nf; ++f) {
    const int c = s.friction_rows[static_cast<std::size_t>(f)];
    next_.emplace_back(key(contacts[static_cast<std::size_t>(s.contacts[static_cast<std::size_t>(c)])], slot[static_cast<std::size_t>(f)]),
                       point(nc + f));
  }
}

void ProximalCenters::commit() {
  std::sort(next_.begin(), next_.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  stored_.swap(next_);
  next_.clear();
}

void ProximalCenters::save(StateWriter& out) const {
  out.put_u64(stored_.size());
  for (const auto& [k, v] : stored_) {
    for (int x : k) out.put_i64(x);
    out.put_double(v);
  }
}

void ProximalCenters::load(StateReader& in) {
  const std::uint64_t n = in.get_u64();
  if (n > in.remaining() / (8 * (std::tuple_size<Key>::value + 1))) in.fail("a centre count of " + std::to_string(n) + " exceeds the bytes left");
  stored_.assign(static_cast<std::size_t>(n), {});
  for (auto& [k, v] : stored_) {
    for (int& x : k) x = static_cast<int>(in.get_int(INT32_MIN, INT32_MAX, "a contact key"));
    v = in.get_double();
  }
  for (std::size_t i = 1; i < stored_.size(); ++i)
    if (!(stored_[i - 1].first < stored_[i].first)) in.fail("proximal centres out of order");
  next_.clear();
}

void ProximalCenters::clear() {
  stored_.clear();
  next_.clear();
}

}  // namespace lcprelax::learn::detail
