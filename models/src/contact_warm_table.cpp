// ContactWarmTable (contact_warm_table.hpp): writes sorted by (key, order), then merged
// per key in write order.
#include <lcprelax/models/contact_warm_table.hpp>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace lcprelax {

std::string contact_warm_record_error(const ContactWarmRecord& r, int bodies) {
  const ContactKey& k = r.key;
  if (k[0] < 0 || k[0] >= bodies) return "body a = " + std::to_string(k[0]) + " is not a body index";
  if (k[1] < -1 || k[1] >= bodies) return "body b = " + std::to_string(k[1]) + " is neither a body index nor -1";
  if (k[2] < 0 || k[2] > 2) return "static kind = " + std::to_string(k[2]) + " is not 0, 1 or 2";
  if (k[3] < -1) return "static index = " + std::to_string(k[3]) + " is below -1";
  if (k[4] < 0) return "ordinal = " + std::to_string(k[4]) + " is negative";
  if (!(r.normal == 0.0 || r.normal == 1.0)) return "normal code must be 0 or 1";
  if (!(r.friction >= 0.0 && r.friction <= 7.0 && std::floor(r.friction) == r.friction))
    return "friction code must be an integer in 0..7";
  return {};
}

void ContactWarmTable::clear() {
  writes_.clear();
  keys_.clear();
  entries_.clear();
}

void ContactWarmTable::finish() {
  // std::sort works in place (no allocation); the order field makes the sort total, so
  // the merge below sees each key's writes in the order they were made. Writes made in key
  // order (the simulator's, in contact order) are already sorted: one pass checks it.
  auto less = [](const Write& a, const Write& b) { return std::tie(a.key, a.order) < std::tie(b.key, b.order); };
  if (!std::is_sorted(writes_.begin(), writes_.end(), less)) std::sort(writes_.begin(), writes_.end(), less);
  keys_.clear();
  entries_.clear();
  keys_.reserve(writes_.size());
  entries_.reserve(writes_.size());
  for (const Write& w : writes_) {
    if (keys_.empty() || keys_.back() != w.key) {
      keys_.push_back(w.key);
      entries_.emplace_back();
    }
    Entry& e = entries_.back();
    switch (w.field) {
      case Field::normal: e.normal = w.code; break;
      case Field::friction: e.friction = w.code; break;
      case Field::regularized: e.regularized = w.code != 0.0; break;
    }
  }
}

const ContactWarmTable::Entry* ContactWarmTable::find(const ContactKey& key) const {
  const auto it = std::lower_bound(keys_.begin(), keys_.end(), key);
  if (it == keys_.end() || *it != key) return nullptr;
  return &entries_[static_cast<std::size_t>(it - keys_.begin())];
}

void ContactWarmTable::find_sorted(const std::vector<ContactKey>& keys, std::vector<const Entry*>& out) const {
  out.assign(keys.size(), nullptr);
  if (std::adjacent_find(keys.begin(), keys.end(), [](const ContactKey& a, const ContactKey& b) { return !(a < b); }) !=
      keys.end()) {
    for (std::size_t i = 0; i < keys.size(); ++i) out[i] = find(keys[i]);
    return;
  }
  std::size_t t = 0;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    while (t < keys_.size() && keys_[t] < keys[i]) ++t;
    if (t < keys_.size() && keys_[t] == keys[i]) out[i] = &entries_[t];
  }
}

std::vector<ContactWarmRecord> ContactWarmTable::records() const {
  std::vector<ContactWarmRecord> out(keys_.size());
  for (std::size_t i = 0; i < keys_.size(); ++i) out[i] = {keys_[i], entries_[i].normal, entries_[i].friction, entries_[i].regularized};
  return out;
}

void ContactWarmTable::assign(const std::vector<ContactWarmRecord>& records) {
  clear();
  for (const ContactWarmRecord& r : records) {
    set_normal(r.key, r.normal);
    set_friction(r.key, r.friction);
    if (r.regularized) set_regularized(r.key, true);
  }
  finish();
}

}  // namespace lcprelax
