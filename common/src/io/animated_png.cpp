#include "kerf/io/animated_png.hpp"

#include "kerf/app/input_error.hpp"

#include <array>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

namespace kerf {

namespace {

using Bytes = std::vector<unsigned char>;

constexpr std::array<unsigned char, 8> png_signature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

/// The CRC-32 of PNG (ISO 3309, polynomial 0xedb88320), over a chunk's type and data.
std::uint32_t crc32(const Bytes& bytes) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xffffffffu;
  for (const unsigned char b : bytes) c = table[(c ^ b) & 0xffu] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

void put32(Bytes& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<unsigned char>((v >> shift) & 0xffu));
}
void put16(Bytes& out, std::uint16_t v) {
  out.push_back(static_cast<unsigned char>(v >> 8));
  out.push_back(static_cast<unsigned char>(v & 0xffu));
}
std::uint32_t get32(const Bytes& in, std::size_t at) {
  return (std::uint32_t{in[at]} << 24) | (std::uint32_t{in[at + 1]} << 16) | (std::uint32_t{in[at + 2]} << 8) | std::uint32_t{in[at + 3]};
}

struct Chunk {
  std::string type;
  Bytes data;
};

/// The chunks of a PNG file, each checked to lie inside the file.
std::vector<Chunk> read_chunks(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), "PNG", "cannot open the file");
  const Bytes bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < 8 || !std::equal(png_signature.begin(), png_signature.end(), bytes.begin()))
    throw InputError(file.string(), "PNG", "not a PNG file (no PNG signature)");
  std::vector<Chunk> chunks;
  std::size_t at = 8;
  while (at + 12 <= bytes.size()) {
    const std::uint32_t length = get32(bytes, at);
    if (length > bytes.size() - at - 12) throw InputError(file.string(), "PNG", "a chunk runs past the end of the file");
    Chunk chunk;
    chunk.type.assign(bytes.begin() + static_cast<std::ptrdiff_t>(at + 4), bytes.begin() + static_cast<std::ptrdiff_t>(at + 8));
    chunk.data.assign(bytes.begin() + static_cast<std::ptrdiff_t>(at + 8), bytes.begin() + static_cast<std::ptrdiff_t>(at + 8 + length));
    at += 12 + length;
    const bool end = chunk.type == "IEND";
    chunks.push_back(std::move(chunk));
    if (end) break;
  }
  if (chunks.empty() || chunks.front().type != "IHDR" || chunks.front().data.size() != 13)
    throw InputError(file.string(), "PNG", "the first chunk is not a 13-byte IHDR");
  return chunks;
}

void write_chunk(std::ofstream& out, const std::string& type, const Bytes& data) {
  Bytes length;
  put32(length, static_cast<std::uint32_t>(data.size()));
  Bytes typed(type.begin(), type.end());
  typed.insert(typed.end(), data.begin(), data.end());
  Bytes crc;
  put32(crc, crc32(typed));
  out.write(reinterpret_cast<const char*>(length.data()), 4);
  out.write(reinterpret_cast<const char*>(typed.data()), static_cast<std::streamsize>(typed.size()));
  out.write(reinterpret_cast<const char*>(crc.data()), 4);
}

} // namespace

void write_animated_png(const std::vector<std::filesystem::path>& frames, const std::filesystem::path& file, int delay_ms) {
  if (frames.empty()) throw std::invalid_argument("write_animated_png: no frames");
  if (delay_ms < 1 || delay_ms > 65535) throw std::invalid_argument("write_animated_png: the delay must lie in [1, 65535] ms");
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary);
  if (!out) throw InputError(file.string(), "write", "cannot open the file");
  out.write(reinterpret_cast<const char*>(png_signature.data()), png_signature.size());

  std::uint32_t sequence = 0;
  Bytes header;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const std::vector<Chunk> chunks = read_chunks(frames[f]);
    if (f == 0) {
      header = chunks.front().data;
      write_chunk(out, "IHDR", header);
      Bytes control; // acTL: the number of frames, and 0 plays: loop forever
      put32(control, static_cast<std::uint32_t>(frames.size()));
      put32(control, 0);
      write_chunk(out, "acTL", control);
    } else if (chunks.front().data != header) {
      throw InputError(frames[f].string(), "PNG", "its size, bit depth or colour type differ from the first frame's (" + frames[0].string() + ")");
    }
    Bytes frame; // fcTL: the whole picture, shown delay_ms / 1000 s, replaced by the next
    put32(frame, sequence++);
    put32(frame, get32(header, 0));
    put32(frame, get32(header, 4));
    put32(frame, 0);
    put32(frame, 0);
    put16(frame, static_cast<std::uint16_t>(delay_ms));
    put16(frame, 1000);
    frame.push_back(0); // dispose_op: none
    frame.push_back(0); // blend_op: source
    write_chunk(out, "fcTL", frame);
    bool any = false;
    for (const Chunk& chunk : chunks) {
      if (chunk.type != "IDAT") continue;
      any = true;
      if (f == 0) {
        write_chunk(out, "IDAT", chunk.data);
      } else {
        Bytes data;
        put32(data, sequence++);
        data.insert(data.end(), chunk.data.begin(), chunk.data.end());
        write_chunk(out, "fdAT", data);
      }
    }
    if (!any) throw InputError(frames[f].string(), "PNG", "no image data (IDAT chunk)");
  }
  write_chunk(out, "IEND", {});
  if (!out) throw InputError(file.string(), "write", "writing failed");
}

} // namespace kerf
