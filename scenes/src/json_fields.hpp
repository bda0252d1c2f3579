#pragma once
// Internal: typed, path-aware access to nlohmann JSON values for the scene reader and
// writer. Every failure throws lcprelax::InputError "PATH: message", where PATH is the
// field path in the document ("bodies[2].vertices[0]", "friction.default"); the empty path
// is the document itself.
#include <lcprelax/world/world.hpp>

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <string>
#include <string_view>

namespace lcprelax::scene_json {

using Json = nlohmann::ordered_json;

/// "PATH: message" (or "message" for the document itself) as an InputError.
[[noreturn]] void fail(const std::string& path, const std::string& message);

/// PATH.key (key alone at the top level) and PATH[i].
std::string member(const std::string& path, std::string_view key);
std::string element(const std::string& path, std::size_t index);

/// Parses JSON text, rejecting duplicate keys ("duplicate key 'k' in PATH"); syntax errors
/// become "invalid JSON: ...".
Json parse_json(std::string_view text);

/// Checks that `j` is an object whose keys are all in `allowed` ("unknown key 'k' in PATH").
void expect_object(const Json& j, const std::string& path,
                   std::initializer_list<std::string_view> allowed);

/// The member `key` of object `j`, or nullptr.
const Json* find(const Json& j, std::string_view key);
/// The member `key` of object `j`; "PATH: missing required key 'key'" when absent.
const Json& require(const Json& j, const std::string& path, std::string_view key);

double number(const Json& j, const std::string& path);  ///< finite number
long long integer(const Json& j, const std::string& path, long long lo, long long hi);
bool boolean(const Json& j, const std::string& path);
std::string string(const Json& j, const std::string& path);
const Json& array(const Json& j, const std::string& path);
Vec2 vec2(const Json& j, const std::string& path);  ///< [x, y], finite

/// Writer side: a JSON number, or "PATH: not finite" (JSON cannot hold NaN/Inf).
Json finite(double value, const std::string& path);
Json finite(const Vec2& value, const std::string& path);

/// Pretty text: objects one member per line (2-space indent), arrays of scalars and arrays
/// of arrays of scalars on one line; numbers with nlohmann's round-trip formatting.
std::string pretty(const Json& j);

}  // namespace lcprelax::scene_json
