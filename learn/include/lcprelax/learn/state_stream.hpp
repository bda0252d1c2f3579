#pragma once
// Exact binary encoding of training state for checkpoints (checkpoint.hpp).
//
// StateWriter appends values to a byte string; StateReader reads them back in the same
// order. Every value is stored exactly and independently of the machine: integers as
// 8-byte little-endian two's complement, doubles as the little-endian bytes of their
// IEEE-754 bit pattern (so NaN payloads, −0.0 and subnormals survive), strings, vectors and
// bit lists with an 8-byte length first. There are no type tags: reader and writer agree on
// the layout, and the checkpoint's version and checksum guard it.
//
// StateReader never reads past its buffer and never allocates more than the bytes left can
// hold: a truncated or corrupt stream throws InputError ("<what>: truncated ..." or
// "<what>: ... length N exceeds the bytes left"), where `what` names the source (e.g. the
// checkpoint file and the section being read).
#include <lcprelax/sparse/types.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace lcprelax::learn {

class StateWriter {
 public:
  void put_u64(std::uint64_t v);
  void put_i64(std::int64_t v) { put_u64(static_cast<std::uint64_t>(v)); }
  void put_bool(bool v) { put_u64(v ? 1u : 0u); }
  void put_double(double v);
  void put_string(const std::string& s);
  void put_vector(const Vector& v);
  void put_doubles(const std::vector<double>& v);
  void put_bools(const std::vector<bool>& v);
  void put_ints(const std::vector<int>& v);
  void put_indices(const std::vector<Index>& v);

  const std::string& bytes() const { return bytes_; }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class StateReader {
 public:
  /// Reads `bytes` (kept by reference: it must outlive the reader); `what` prefixes errors.
  StateReader(const std::string& bytes, std::string what);

  std::uint64_t get_u64();
  std::int64_t get_i64() { return static_cast<std::int64_t>(get_u64()); }
  bool get_bool();
  /// An integer in [lo, hi]; InputError naming `field` otherwise.
  std::int64_t get_int(std::int64_t lo, std::int64_t hi, const char* field);
  double get_double();
  std::string get_string();
  Vector get_vector();
  std::vector<double> get_doubles();
  std::vector<bool> get_bools();
  std::vector<int> get_ints();
  std::vector<Index> get_indices();

  /// Reads a string and fails ("holds the state of '<x>', expected '<tag>'") unless it is
  /// `tag`: a section's first value, naming what wrote it.
  void expect_tag(const std::string& tag);
  /// A count that must be `expected` (or 0 when `or_zero`); fails naming `field`.
  std::size_t get_count(std::size_t expected, bool or_zero, const char* field);

  /// Bytes not yet read.
  std::size_t remaining() const { return bytes_.size() - pos_; }
  /// Throws InputError unless every byte has been read.
  void expect_end() const;
  /// Changes the error prefix (e.g. to name the section being read).
  void set_what(std::string what) { what_ = std::move(what); }
  const std::string& what() const { return what_; }
  /// Throws InputError("<what>: <message>").
  [[noreturn]] void fail(const std::string& message) const;

 private:
  /// A length field whose elements take `element_bytes` bytes each (≥ 1 byte per element).
  std::size_t get_length(std::size_t element_bytes);
  void need(std::size_t n) const;

  const std::string& bytes_;
  std::size_t pos_ = 0;
  std::string what_;
};

}  // namespace lcprelax::learn
