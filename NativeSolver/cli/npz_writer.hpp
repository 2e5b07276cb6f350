#pragma once
// A numpy .npz file (docs/daylight.md, "skymtx"): a ZIP archive of .npy arrays, stored, or
// deflated as numpy.savez_compressed writes them (numpy.load reads both; NPY format 1.0,
// little-endian). Built in memory, then written atomically by the caller.
#include <cstdint>
#include <string>
#include <vector>

namespace lightsolver::cli {

/// An .npz archive being assembled.
class NpzWriter {
 public:
  /// `deflate`: each array compressed (zlib, ZIP method 8); else stored.
  explicit NpzWriter(bool deflate = false) : deflate_(deflate) {}
  /// Adds `name`.npy: `dtype` a numpy descr ("<f4", "<i4", "|u1"), `shape` its dimensions,
  /// `data` the bytes in C order.
  void add(const std::string& name, const std::string& dtype, const std::vector<std::size_t>& shape,
           const void* data, std::size_t bytes);
  /// Adds `name`.npy holding `v`, whose element type `dtype` describes.
  template <class T>
  void add(const std::string& name, const std::string& dtype, const std::vector<T>& v,
           const std::vector<std::size_t>& shape) {
    add(name, dtype, shape, v.data(), v.size() * sizeof(T));
  }
  /// The whole archive (central directory appended).
  std::string finish() const;

 private:
  struct Entry {
    std::string name;
    std::uint32_t crc = 0, size = 0, packed = 0, offset = 0, method = 0;
  };
  bool deflate_ = false;
  std::string body_;
  std::vector<Entry> entries_;
};

}  // namespace lightsolver::cli
