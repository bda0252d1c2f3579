// Exact binary encoding of training state (state_stream.hpp).
#include <lcprelax/learn/state_stream.hpp>
#include <lcprelax/core/errors.hpp>

#include <cstring>

namespace lcprelax::learn {

namespace {

std::uint64_t bits_of(double v) {
  std::uint64_t b = 0;
  static_assert(sizeof b == sizeof v, "IEEE-754 binary64 expected");
  std::memcpy(&b, &v, sizeof b);
  return b;
}

double double_of(std::uint64_t b) {
  double v = 0.0;
  std::memcpy(&v, &b, sizeof v);
  return v;
}

}  // namespace

void StateWriter::put_u64(std::uint64_t v) {
  char b[8];
  for (int i = 0; i < 8; ++i) b[i] = static_cast<char>((v >> (8 * i)) & 0xffu);
  bytes_.append(b, 8);
}

void StateWriter::put_double(double v) { put_u64(bits_of(v)); }

void StateWriter::put_string(const std::string& s) {
  put_u64(s.size());
  bytes_.append(s);
}

void StateWriter::put_vector(const Vector& v) {
  put_u64(static_cast<std::uint64_t>(v.size()));
  for (Index i = 0; i < v.size(); ++i) put_double(v(i));
}

void StateWriter::put_doubles(const std::vector<double>& v) {
  put_u64(v.size());
  for (double x : v) put_double(x);
}

void StateWriter::put_bools(const std::vector<bool>& v) {
  put_u64(v.size());
  for (bool x : v) bytes_.push_back(x ? '\1' : '\0');
}

void StateWriter::put_ints(const std::vector<int>& v) {
  put_u64(v.size());
  for (int x : v) put_i64(x);
}

void StateWriter::put_indices(const std::vector<Index>& v) {
  put_u64(v.size());
  for (Index x : v) put_i64(static_cast<std::int64_t>(x));
}

StateReader::StateReader(const std::string& bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}

void StateReader::fail(const std::string& message) const { throw InputError(what_ + ": " + message); }

void StateReader::need(std::size_t n) const {
  if (n > remaining())
    fail("truncated (needs " + std::to_string(n) + " more bytes at offset " + std::to_string(pos_) + ", " +
         std::to_string(remaining()) + " left)");
}

std::uint64_t StateReader::get_u64() {
  need(8);
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i)
    v |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes_[pos_ + static_cast<std::size_t>(i)])) << (8 * i);
  pos_ += 8;
  return v;
}

bool StateReader::get_bool() {
  const std::uint64_t v = get_u64();
  if (v > 1) fail("a flag holds " + std::to_string(v) + ", expected 0 or 1");
  return v == 1;
}

std::int64_t StateReader::get_int(std::int64_t lo, std::int64_t hi, const char* field) {
  const std::int64_t v = get_i64();
  if (v < lo || v > hi)
    fail(std::string(field) + " = " + std::to_string(v) + " is outside [" + std::to_string(lo) + ", " +
         std::to_string(hi) + "]");
  return v;
}

double StateReader::get_double() { return double_of(get_u64()); }

std::size_t StateReader::get_length(std::size_t element_bytes) {
  const std::uint64_t n = get_u64();
  if (n > remaining() / element_bytes)
    fail("a length of " + std::to_string(n) + " exceeds the " + std::to_string(remaining()) + " bytes left");
  return static_cast<std::size_t>(n);
}

std::string StateReader::get_string() {
  const std::size_t n = get_length(1);
  std::string s = bytes_.substr(pos_, n);
  pos_ += n;
  return s;
}

Vector StateReader::get_vector() {
  const std::size_t n = get_length(8);
  Vector v(static_cast<Index>(n));
  for (std::size_t i = 0; i < n; ++i) v(static_cast<Index>(i)) = get_double();
  return v;
}

std::vector<double> StateReader::get_doubles() {
  const std::size_t n = get_length(8);
  std::vector<double> v(n);
  for (double& x : v) x = get_double();
  return v;
}

std::vector<bool> StateReader::get_bools() {
  const std::size_t n = get_length(1);
  std::vector<bool> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    const char c = bytes_[pos_++];
    if (c != '\0' && c != '\1') fail("a bit list holds the byte " + std::to_string(static_cast<unsigned char>(c)));
    v[i] = c == '\1';
  }
  return v;
}

std::vector<int> StateReader::get_ints() {
  const std::size_t n = get_length(8);
  std::vector<int> v(n);
  for (int& x : v) x = static_cast<int>(get_int(INT32_MIN, INT32_MAX, "an int"));
  return v;
}

std::vector<Index> StateReader::get_indices() {
  const std::size_t n = get_length(8);
  std::vector<Index> v(n);
  for (Index& x : v) x = static_cast<Index>(get_i64());
  return v;
}

void StateReader::expect_tag(const std::string& tag) {
  std::string got = get_string();
  if (got != tag) {
    if (got.size() > 60) got = got.substr(0, 60) + "...";
    fail("holds the state of '" + got + "', expected '" + tag + "'");
  }
}

std::size_t StateReader::get_count(std::size_t expected, bool or_zero, const char* field) {
  const std::uint64_t n = get_u64();
  if (n != expected && !(or_zero && n == 0))
    fail(std::string(field) + ": " + std::to_string(n) + " entries, expected " + std::to_string(expected));
  return static_cast<std::size_t>(n);
}

void StateReader::expect_end() const {
  if (remaining() != 0) fail(std::to_string(remaining()) + " unexpected bytes at the end");
}

}  // namespace lcprelax::learn
