// The Simulator's warm-start state as values (simulator.hpp set_warm_start_state): every
// record checked (contact_warm_record_error), then loaded into the table the next step reads.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/models/simulator.hpp>

#include <string>

namespace lcprelax {

void Simulator::set_warm_start_state(const std::vector<ContactWarmRecord>& records) {
  const int bodies = static_cast<int>(world_.bodies.size());
  for (std::size_t i = 0; i < records.size(); ++i)
    if (const std::string e = contact_warm_record_error(records[i], bodies); !e.empty())
      throw InputError("warm_start[" + std::to_string(i) + "]: " + e);
  warm_.assign(records);
}

}  // namespace lcprelax
