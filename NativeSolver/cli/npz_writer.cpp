// A ZIP of NPY 1.0 arrays, stored or deflated (zlib): PKWARE's APPNOTE local headers, central
// directory and end record.
#include "npz_writer.hpp"

#include <zlib.h>

#include <stdexcept>

namespace lightsolver::cli {

namespace {

std::uint32_t crc_of(const std::string& s) {
  return static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(s.data()), static_cast<uInt>(s.size())));
}

// Raw deflate (no zlib header: ZIP's method 8), by zlib.
std::string deflated(const std::string& in) {
  z_stream z{};
  if (deflateInit2(&z, 6, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("zlib: deflateInit2 failed");
  std::string out(deflateBound(&z, static_cast<uLong>(in.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
  z.avail_in = static_cast<uInt>(in.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  if (rc != Z_STREAM_END) throw std::runtime_error("zlib: deflate did not finish");
  return out;
}

void put16(std::string& s, std::uint32_t v) {
  s.push_back(static_cast<char>(v & 0xFF));
  s.push_back(static_cast<char>((v >> 8) & 0xFF));
}
void put32(std::string& s, std::uint32_t v) {
  put16(s, v & 0xFFFF);
  put16(s, v >> 16);
}

// NPY 1.0: magic, version, header length, the header dict padded so the data starts at a
// multiple of 64 bytes.
std::string npy(const std::string& dtype, const std::vector<std::size_t>& shape, const void* data,
                std::size_t bytes) {
  std::string dims;
  for (std::size_t d : shape) dims += std::to_string(d) + ", ";
  if (shape.size() > 1) dims.resize(dims.size() - 1);
  std::string header =
      "{'descr': '" + dtype + "', 'fortran_order': False, 'shape': (" + dims + "), }";
  while ((10 + header.size() + 1) % 64 != 0) header.push_back(' ');
  header.push_back('\n');
  std::string out("\x93NUMPY\x01\x00", 8);
  put16(out, static_cast<std::uint32_t>(header.size()));
  out += header;
  out.append(static_cast<const char*>(data), bytes);
  return out;
}

}  // namespace

void NpzWriter::add(const std::string& name, const std::string& dtype,
                    const std::vector<std::size_t>& shape, const void* data, std::size_t bytes) {
  const std::string file = npy(dtype, shape, data, bytes);
  if (file.size() > 0xFFFFFFF0u)
    throw std::runtime_error("an array of the .npz would exceed 4 GB (ZIP64 is not written)");
  const std::string packed = deflate_ ? deflated(file) : std::string();
  const std::string& stored = deflate_ ? packed : file;
  if (body_.size() + stored.size() > 0xFFFFFFF0u)
    throw std::runtime_error("the .npz would exceed 4 GB (ZIP64 is not written)");
  Entry e{name + ".npy",
          crc_of(file),
          static_cast<std::uint32_t>(file.size()),
          static_cast<std::uint32_t>(stored.size()),
          static_cast<std::uint32_t>(body_.size()),
          deflate_ ? 8u : 0u};
  put32(body_, 0x04034b50u);  // local file header
  put16(body_, 20);           // version needed
  put16(body_, 0);            // flags
  put16(body_, e.method);     // 0 stored, 8 deflated
  put16(body_, 0);            // time
  put16(body_, 0x21);         // date: 1980-01-01
  put32(body_, e.crc);
  put32(body_, e.packed);
  put32(body_, e.size);
  put16(body_, static_cast<std::uint32_t>(e.name.size()));
  put16(body_, 0);
  body_ += e.name;
  body_ += stored;
  entries_.push_back(e);
}

std::string NpzWriter::finish() const {
  std::string out = body_, dir;
  for (const Entry& e : entries_) {
    put32(dir, 0x02014b50u);  // central directory header
    put16(dir, 20);           // made by
    put16(dir, 20);           // needed
    put16(dir, 0);            // flags
    put16(dir, e.method);     // 0 stored, 8 deflated
    put16(dir, 0);
    put16(dir, 0x21);
    put32(dir, e.crc);
    put32(dir, e.packed);
    put32(dir, e.size);
    put16(dir, static_cast<std::uint32_t>(e.name.size()));
    put16(dir, 0);  // extra
    put16(dir, 0);  // comment
    put16(dir, 0);  // disk
    put16(dir, 0);  // internal attributes
    put32(dir, 0);  // external attributes
    put32(dir, e.offset);
    dir += e.name;
  }
  const auto dir_offset = static_cast<std::uint32_t>(out.size());
  out += dir;
  put32(out, 0x06054b50u);  // end of central directory
  put16(out, 0);
  put16(out, 0);
  put16(out, static_cast<std::uint32_t>(entries_.size()));
  put16(out, static_cast<std::uint32_t>(entries_.size()));
  put32(out, static_cast<std::uint32_t>(dir.size()));
  put32(out, dir_offset);
  put16(out, 0);
  return out;
}

}  // namespace lightsolver::cli
