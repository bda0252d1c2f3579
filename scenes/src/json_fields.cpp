// Path-aware JSON access for scene files (internal; see json_fields.hpp).
#include "json_fields.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/core/text_input.hpp>

#include <cmath>
#include <set>
#include <vector>

namespace lcprelax::scene_json {

void fail(const std::string& path, const std::string& message) {
  throw InputError(text::clip_message(path.empty() ? message : path + ": " + message));
}

std::string member(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string element(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

namespace {

std::string where(const std::string& path) { return path.empty() ? "the scene" : path; }

// Tracks the path of the value being parsed so that duplicate keys can be reported by path
// (nlohmann keeps the last of duplicate keys silently).
class DuplicateKeyCheck {
 public:
  bool operator()(int /*depth*/, nlohmann::json::parse_event_t event, Json& parsed) {
    using E = nlohmann::json::parse_event_t;
    switch (event) {
      case E::object_start: child(); frames_.push_back({false, "", 0, {}}); break;
      case E::array_start: child(); frames_.push_back({true, "", 0, {}}); break;
      case E::object_end:
      case E::array_end: frames_.pop_back(); break;
      case E::value: child(); break;
      case E::key: {
        Frame& f = frames_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second)
          throw InputError(text::clip_message("duplicate key " + text::quote(f.key) + " in " + where(parent_path())));
        break;
      }
    }
    return true;
  }

 private:
  struct Frame {
    bool is_array;
    std::string key;        // current key (objects)
    std::size_t count;      // children seen so far (arrays)
    std::set<std::string> keys;
  };
  void child() {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().count;
  }
  // Path of the innermost container: each enclosing frame names its current child.
  std::string parent_path() const {
    std::string path;
    for (std::size_t i = 0; i + 1 < frames_.size(); ++i)
      path = frames_[i].is_array ? element(path, frames_[i].count - 1) : member(path, frames_[i].key);
    return path;
  }
  std::vector<Frame> frames_;
};

}  // namespace

Json parse_json(std::string_view text) {
  try {
    return Json::parse(text.begin(), text.end(), DuplicateKeyCheck{});
  } catch (const nlohmann::json::exception& e) {
    throw InputError(text::clip_message(std::string("invalid JSON: ") + e.what()));
  }
}

void expect_object(const Json& j, const std::string& path,
                   std::initializer_list<std::string_view> allowed) {
  if (!j.is_object()) fail(path, std::string("expected an object, got ") + j.type_name());
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool known = false;
    for (std::string_view a : allowed) known = known || it.key() == a;
    if (!known) throw InputError(text::clip_message("unknown key " + text::quote(it.key()) + " in " + where(path)));
  }
}

const Json* find(const Json& j, std::string_view key) {
  const auto it = j.find(std::string(key));
  return it == j.end() ? nullptr : &*it;
}

const Json& require(const Json& j, const std::string& path, std::string_view key) {
  const Json* v = find(j, key);
  if (v == nullptr) fail(path, "missing required key '" + std::string(key) + "'");
  return *v;
}

double number(const Json& j, const std::string& path) {
  if (!j.is_number()) fail(path, std::string("expected a number, got ") + j.type_name());
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail(path, "not finite");
  return v;
}

long long integer(const Json& j, const std::string& path, long long lo, long long hi) {
  if (j.is_number_float()) fail(path, "expected an integer, got " + j.dump());
  if (!j.is_number()) fail(path, std::string("expected an integer, got ") + j.type_name());
  const bool too_big = j.is_number_unsigned() &&
                       j.get<unsigned long long>() > static_cast<unsigned long long>(hi);
  const long long v = too_big ? hi : j.get<long long>();
  if (too_big || v < lo || v > hi)
    fail(path, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + j.dump());
  return v;
}

bool boolean(const Json& j, const std::string& path) {
  if (!j.is_boolean()) fail(path, std::string("expected a boolean, got ") + j.type_name());
  return j.get<bool>();
}

std::string string(const Json& j, const std::string& path) {
  if (!j.is_string()) fail(path, std::string("expected a string, got ") + j.type_name());
  return j.get<std::string>();
}

const Json& array(const Json& j, const std::string& path) {
  if (!j.is_array()) fail(path, std::string("expected an array, got ") + j.type_name());
  return j;
}

Vec2 vec2(const Json& j, const std::string& path) {
  if (!j.is_array() || j.size() != 2)
    fail(path, std::string("expected [x, y], got ") +
                   (j.is_array() ? "an array of " + std::to_string(j.size()) : j.type_name()));
  return Vec2(number(j[0], element(path, 0)), number(j[1], element(path, 1)));
}

Json finite(double value, const std::string& path) {
  if (!std::isfinite(value)) fail(path, "not finite");
  return value;
}

Json finite(const Vec2& value, const std::string& path) {
  return Json::array({finite(value.x(), element(path, 0)), finite(value.y(), element(path, 1))});
}

namespace {

bool scalar(const Json& j) { return !j.is_object() && !j.is_array(); }

bool inline_array(const Json& j) {
  for (const Json& e : j) {
    if (e.is_object()) return false;
    if (e.is_array())
      for (const Json& f : e)
        if (!scalar(f)) return false;
  }
  return true;
}

void emit(const Json& j, int indent, std::string& out) {
  const std::string pad(static_cast<std::size_t>(indent) + 2, ' ');
  if (j.is_object() && !j.empty()) {
    out += "{\n";
    bool first = true;
    for (auto it = j.begin(); it != j.end(); ++it) {
      out += first ? "" : ",\n";
      first = false;
      out += pad + Json(it.key()).dump() + ": ";
      emit(it.value(), indent + 2, out);
    }
    out += "\n" + std::string(static_cast<std::size_t>(indent), ' ') + "}";
  } else if (j.is_array() && !j.empty() && !inline_array(j)) {
    out += "[\n";
    for (std::size_t i = 0; i < j.size(); ++i) {
      out += (i ? ",\n" : "") + pad;
      emit(j[i], indent + 2, out);
    }
    out += "\n" + std::string(static_cast<std::size_t>(indent), ' ') + "]";
  } else if (j.is_array()) {
    out += "[";
    for (std::size_t i = 0; i < j.size(); ++i) {
      out += i ? ", " : "";
      emit(j[i], indent, out);
    }
    out += "]";
  } else {
    out += j.dump();
  }
}

}  // namespace

std::string pretty(const Json& j) {
  std::string out;
  emit(j, 0, out);
  out += "\n";
  return out;
}

}  // namespace lcprelax::scene_json
