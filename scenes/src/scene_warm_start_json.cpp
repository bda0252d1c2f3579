// A scene file's "warm_start" list (scene_warm_start_json.hpp).
#include "scene_warm_start_json.hpp"

#include <climits>

namespace lcprelax::scene_json {

std::vector<ContactWarmRecord> read_warm_start(const Json& list, int bodies) {
  const char* key = "warm_start";
  array(list, key);
  std::vector<ContactWarmRecord> out(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = element(key, i);
    const Json& e = array(list[i], path);
    if (e.size() != 7 && e.size() != 8)
      fail(path,
           "expected 7 or 8 integers [body a, body b, static kind, static index, ordinal, normal, friction"
           "(, regularized)], got " +
               std::to_string(e.size()) + " entries");
    // Bounds per position; a body index needs a body (body a at least one).
    const long long lo[8] = {0, -1, 0, -1, 0, 0, 0, 0};
    const long long hi[8] = {bodies - 1LL, bodies - 1LL, 2, INT_MAX, INT_MAX, 1, 7, 1};
    long long v[8] = {};
    for (std::size_t k = 0; k < e.size(); ++k) v[k] = integer(e[k], element(path, k), lo[k], hi[k]);
    ContactWarmRecord& r = out[i];
    for (std::size_t k = 0; k < 5; ++k) r.key[k] = static_cast<int>(v[k]);
    r.normal = static_cast<double>(v[5]);
    r.friction = static_cast<double>(v[6]);
    r.regularized = v[7] != 0;
  }
  return out;
}

Json warm_start_json(const std::vector<ContactWarmRecord>& records, int bodies) {
  Json list = Json::array();
  for (std::size_t i = 0; i < records.size(); ++i) {
    const ContactWarmRecord& r = records[i];
    if (const std::string e = contact_warm_record_error(r, bodies); !e.empty()) fail(element("warm_start", i), e);
    Json e = Json::array();
    for (int k : r.key) e.push_back(k);
    e.push_back(static_cast<int>(r.normal));
    e.push_back(static_cast<int>(r.friction));
    if (r.regularized) e.push_back(1);  // 7 integers otherwise (files without the flag)
    list.push_back(std::move(e));
  }
  return list;
}

}  // namespace lcprelax::scene_json
