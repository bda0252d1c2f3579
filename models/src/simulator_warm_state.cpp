// The Simulator's warm-start state as values (simulator.hpp warm_start_state,
// set_warm_start_state): checked record by record, then loaded into the table that the
// next step reads.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/models/simulator.hpp>

#include <cmath>
#include <string>

namespace lcprelax {
namespace {

// Why record `r` cannot be a contact's warm-start entry in a world of `bodies` bodies, or "".
std::string warm_record_error(const ContactWarmRecord& r, int bodies) {
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

}  // namespace

void Simulator::set_warm_start_state(const std::vector<ContactWarmRecord>& records) {
  const int bodies = static_cast<int>(world_.bodies.size());
  for (std::size_t i = 0; i < records.size(); ++i)
    if (const std::string e = warm_record_error(records[i], bodies); !e.empty())
      throw InputError("warm_start[" + std::to_string(i) + "]: " + e);
  warm_.assign(records);
}

}  // namespace lcprelax
