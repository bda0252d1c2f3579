// `learn scene --init-from RESULT.json` (learn_init_from.hpp).
#include "learn_init_from.hpp"

#include "cli_common.hpp"

#include <lcprelax/core/errors.hpp>

#include <cmath>
#include <exception>
#include <fstream>

namespace lcprelax::cli {

void set_initial_values_from(const std::string& path, learn::ParameterSet& theta) {
  std::ifstream in(path);
  if (!in) throw InputError("--init-from: cannot read '" + path + "'");
  Json j;
  try {
    j = Json::parse(in);
  } catch (const std::exception& e) {
    throw InputError("--init-from '" + path + "': not JSON (" + e.what() + ")");
  }
  if (!j.is_object() || !j.contains("learned") || !j["learned"].is_object())
    throw InputError("--init-from '" + path + "': no \"learned\" object (a JSON result of learn scene --json)");
  const Json& learned = j["learned"];
  Vector v = theta.values();
  std::size_t used = 0;
  for (Index k = 0; k < theta.size(); ++k) {
    const auto it = learned.find(theta[k].name);
    if (it == learned.end()) {
      if (theta[k].learn)
        throw InputError("--init-from '" + path + "': learned." + theta[k].name + " is missing (learned by this run)");
      continue;
    }
    if (!it->is_number() || !std::isfinite(it->get<double>()))
      throw InputError("--init-from '" + path + "': learned." + theta[k].name + " is not a finite number");
    v(k) = it->get<double>();
    ++used;
  }
  if (used != learned.size())
    throw InputError("--init-from '" + path + "': learned has " + std::to_string(learned.size()) +
                     " entries, of which only " + std::to_string(used) + " name a parameter of this scene");
  theta.set_values(v);
}

}  // namespace lcprelax::cli
