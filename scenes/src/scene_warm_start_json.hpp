#pragma once
// Internal: a scene file's "warm_start" list (scene_json.hpp): each contact's part of the
// last step's Lemke basis or active set (models/contact_warm_table.hpp ContactWarmRecord),
// one array [body a, body b, static kind, static index, ordinal, normal code, friction
// code] per contact.
#include "json_fields.hpp"

#include <lcprelax/models/contact_warm_table.hpp>

#include <vector>

namespace lcprelax::scene_json {

/// Reads the list at path "warm_start" for a world of `bodies` bodies: each entry an array
/// of 7 or 8 integers, body a in [0, bodies), body b in [−1, bodies), static kind in 0..2,
/// static index ≥ −1, ordinal ≥ 0, normal code 0 or 1, friction code 0..7, and optionally
/// regularized 0 or 1 (default 0) (InputError naming the entry otherwise, e.g.
/// "warm_start[4][5]: must be in [0, 1], got 2").
std::vector<ContactWarmRecord> read_warm_start(const Json& list, int bodies);

/// The list as written by write_scene for a world of `bodies` bodies (the codes as integers,
/// an 8th integer 1 only for a regularized record; InputError naming the record for one that
/// contact_warm_record_error refuses).
Json warm_start_json(const std::vector<ContactWarmRecord>& records, int bodies);

}  // namespace lcprelax::scene_json
