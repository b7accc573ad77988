// PNG frames joined into an animated PNG (io/animated_png.hpp), checked byte by byte against
// the APNG specification: the signature, IHDR first, acTL with the number of frames and 0
// plays (loop forever), one fcTL per frame, the fcTL and fdAT sequence numbers counting 0, 1, 2,
// ... through both kinds of chunk, every chunk's CRC-32 (computed here bit by bit, not with the
// library's table), and each frame's compressed data copied unchanged. A reader without APNG
// (VTK's) shows frame 0; the other frames, unpacked into PNGs of their own, read back as the
// images they were made from.
#include "kerf/app/input_error.hpp"
#include "kerf/io/animated_png.hpp"
#include "kerf/render/write_png.hpp"
#include "support/run_program.hpp"

#include <doctest/doctest.h>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkSmartPointer.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using Bytes = std::vector<unsigned char>;

// A w x h RGB image: a colour of its own, with a gradient so that rows and columns differ.
vtkSmartPointer<vtkImageData> coloured_image(int w, int h, std::array<int, 3> colour) {
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      auto* pixel = static_cast<unsigned char*>(image->GetScalarPointer(i, j, 0));
      for (std::size_t c = 0; c < 3; ++c) pixel[c] = static_cast<unsigned char>((colour[c] + 7 * i + 3 * j) % 256);
    }
  return image;
}

// The image's bytes, row by row, as VTK holds them.
Bytes pixels(vtkImageData& image) {
  const int* dims = image.GetDimensions();
  const auto* first = static_cast<const unsigned char*>(image.GetScalarPointer());
  return Bytes(first, first + static_cast<std::size_t>(dims[0]) * dims[1] * image.GetNumberOfScalarComponents());
}

Bytes read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return Bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::uint32_t get32(const Bytes& b, std::size_t at) {
  return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) | (std::uint32_t{b[at + 2]} << 8) | std::uint32_t{b[at + 3]};
}
std::uint16_t get16(const Bytes& b, std::size_t at) { return static_cast<std::uint16_t>((b[at] << 8) | b[at + 1]); }

// CRC-32 as the PNG specification's annex D defines it, one bit at a time.
std::uint32_t crc32_bitwise(const Bytes& bytes) {
  std::uint32_t c = 0xffffffffu;
  for (const unsigned char byte : bytes) {
    c ^= byte;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

struct Chunk {
  std::string type;
  Bytes data;
  bool crc_ok = false;
};

// The chunks after the signature; the test fails if a chunk runs past the end.
std::vector<Chunk> parse_chunks(const Bytes& file) {
  std::vector<Chunk> chunks;
  std::size_t at = 8;
  while (at < file.size()) {
    REQUIRE(at + 12 <= file.size());
    const std::uint32_t length = get32(file, at);
    REQUIRE(at + 12 + length <= file.size());
    Chunk chunk;
    chunk.type.assign(file.begin() + static_cast<std::ptrdiff_t>(at + 4), file.begin() + static_cast<std::ptrdiff_t>(at + 8));
    chunk.data.assign(file.begin() + static_cast<std::ptrdiff_t>(at + 8), file.begin() + static_cast<std::ptrdiff_t>(at + 8 + length));
    const Bytes typed(file.begin() + static_cast<std::ptrdiff_t>(at + 4), file.begin() + static_cast<std::ptrdiff_t>(at + 8 + length));
    chunk.crc_ok = crc32_bitwise(typed) == get32(file, at + 8 + length);
    chunks.push_back(std::move(chunk));
    at += 12 + length;
  }
  return chunks;
}

void put32(Bytes& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<unsigned char>((v >> shift) & 0xffu));
}

void append_chunk(Bytes& out, const std::string& type, const Bytes& data) {
  put32(out, static_cast<std::uint32_t>(data.size()));
  Bytes typed(type.begin(), type.end());
  typed.insert(typed.end(), data.begin(), data.end());
  out.insert(out.end(), typed.begin(), typed.end());
  put32(out, crc32_bitwise(typed));
}

const Bytes signature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

vtkSmartPointer<vtkImageData> read_png(const std::filesystem::path& file) {
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(file.string().c_str());
  reader->Update();
  return reader->GetOutput();
}

std::string error_of(const std::vector<std::filesystem::path>& frames, const std::filesystem::path& out) {
  try {
    kerf::write_animated_png(frames, out, 100);
  } catch (const kerf::InputError& error) {
    return error.what();
  }
  return "";
}

} // namespace

TEST_CASE("animated PNG: three frames joined, chunk by chunk as the APNG specification has them") {
  const std::filesystem::path dir = kerf_test::fresh_dir("animated_png");
  const std::array<std::array<int, 3>, 3> colours = {{{200, 30, 30}, {30, 200, 30}, {30, 30, 200}}};
  std::vector<std::filesystem::path> frames;
  std::vector<Bytes> frame_pixels;
  for (std::size_t f = 0; f < colours.size(); ++f) {
    const vtkSmartPointer<vtkImageData> image = coloured_image(24, 16, colours[f]);
    frames.push_back(dir / ("frame_" + std::to_string(f) + ".png"));
    kerf::write_png(frames.back(), *image);
    frame_pixels.push_back(pixels(*image));
  }
  REQUIRE(frame_pixels[0] != frame_pixels[1]);
  const std::filesystem::path film = dir / "film.png";
  const int delay = 140;
  kerf::write_animated_png(frames, film, delay);

  const Bytes bytes = read_bytes(film);
  REQUIRE(bytes.size() > 8);
  CHECK(Bytes(bytes.begin(), bytes.begin() + 8) == signature);
  const std::vector<Chunk> chunks = parse_chunks(bytes);
  REQUIRE(chunks.size() >= 7);
  for (const Chunk& chunk : chunks) {
    CAPTURE(chunk.type);
    CHECK(chunk.crc_ok);
  }
  CHECK(chunks.front().type == "IHDR");
  CHECK(chunks.back().type == "IEND");
  CHECK(chunks.back().data.empty());
  const Bytes& header = chunks.front().data;
  REQUIRE(header.size() == 13);
  CHECK(get32(header, 0) == 24);
  CHECK(get32(header, 4) == 16);
  // acTL comes before the first IDAT: 3 frames, 0 plays.
  CHECK(chunks[1].type == "acTL");
  REQUIRE(chunks[1].data.size() == 8);
  CHECK(get32(chunks[1].data, 0) == 3);
  CHECK(get32(chunks[1].data, 4) == 0);

  // The frames in order: fcTL, then frame 0's IDATs, or a later frame's fdATs.
  std::uint32_t next_sequence = 0;
  int frame = -1;
  std::vector<Bytes> frame_data(3);
  for (std::size_t k = 2; k + 1 < chunks.size(); ++k) {
    const Chunk& chunk = chunks[k];
    CAPTURE(k);
    CAPTURE(chunk.type);
    if (chunk.type == "fcTL") {
      ++frame;
      REQUIRE(chunk.data.size() == 26);
      CHECK(get32(chunk.data, 0) == next_sequence++);
      CHECK(get32(chunk.data, 4) == 24);  // width
      CHECK(get32(chunk.data, 8) == 16);  // height
      CHECK(get32(chunk.data, 12) == 0);  // x offset
      CHECK(get32(chunk.data, 16) == 0);  // y offset
      CHECK(get16(chunk.data, 20) == delay); // delay numerator
      CHECK(get16(chunk.data, 22) == 1000);  // delay denominator: milliseconds
      CHECK(chunk.data[24] == 0);            // dispose_op none
      CHECK(chunk.data[25] == 0);            // blend_op source
    } else if (chunk.type == "IDAT") {
      CHECK(frame == 0);
      frame_data[0].insert(frame_data[0].end(), chunk.data.begin(), chunk.data.end());
    } else if (chunk.type == "fdAT") {
      REQUIRE(frame >= 1);
      REQUIRE(chunk.data.size() > 4);
      CHECK(get32(chunk.data, 0) == next_sequence++);
      frame_data[static_cast<std::size_t>(frame)].insert(frame_data[static_cast<std::size_t>(frame)].end(), chunk.data.begin() + 4, chunk.data.end());
    } else {
      FAIL("unexpected chunk " << chunk.type);
    }
  }
  CHECK(frame == 2);

  // Each frame's compressed data is its file's, unchanged.
  for (std::size_t f = 0; f < 3; ++f) {
    Bytes original;
    for (const Chunk& chunk : parse_chunks(read_bytes(frames[f])))
      if (chunk.type == "IDAT") original.insert(original.end(), chunk.data.begin(), chunk.data.end());
    CAPTURE(f);
    CHECK(frame_data[f] == original);
  }

  // A reader without APNG shows frame 0.
  CHECK(pixels(*read_png(film)) == frame_pixels[0]);
  // Frames 1 and 2, each unpacked into a PNG of its own (IHDR, its data as IDAT, IEND), read back
  // as the images they were made from.
  for (std::size_t f = 1; f < 3; ++f) {
    Bytes single = signature;
    append_chunk(single, "IHDR", header);
    append_chunk(single, "IDAT", frame_data[f]);
    append_chunk(single, "IEND", {});
    const std::filesystem::path file = dir / ("unpacked_" + std::to_string(f) + ".png");
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(single.data()), static_cast<std::streamsize>(single.size()));
    CAPTURE(f);
    CHECK(pixels(*read_png(file)) == frame_pixels[f]);
  }
}

TEST_CASE("animated PNG: a frame of another size, a file that is not a PNG, no frames and a bad delay are refused") {
  const std::filesystem::path dir = kerf_test::fresh_dir("animated_png_errors");
  const std::filesystem::path a = dir / "a.png", b = dir / "b_larger.png", text = dir / "not_a_png.png";
  kerf::write_png(a, *coloured_image(12, 8, {10, 20, 30}));
  kerf::write_png(b, *coloured_image(12, 9, {10, 20, 30}));
  kerf_test::write_text(text, "this is text, not a picture\n");

  const std::string size = error_of({a, b}, dir / "size.png");
  CHECK(size.find(b.string() + ": PNG:") == 0); // names the frame that differs, first
  CHECK(size.find("differ") != std::string::npos);
  const std::string not_png = error_of({a, text}, dir / "text.png");
  CHECK(not_png.find(text.string() + ": PNG:") == 0);
  CHECK(not_png.find("not a PNG") != std::string::npos);
  const std::string first_not_png = error_of({text, a}, dir / "text_first.png");
  CHECK(first_not_png.find(text.string() + ": PNG:") == 0);
  const std::string missing = error_of({a, dir / "missing.png"}, dir / "missing_out.png");
  CHECK(missing.find((dir / "missing.png").string() + ": PNG:") == 0);

  CHECK_THROWS_AS(kerf::write_animated_png({}, dir / "none.png", 100), std::invalid_argument);
  CHECK_THROWS_AS(kerf::write_animated_png({a}, dir / "zero.png", 0), std::invalid_argument);
  CHECK_THROWS_AS(kerf::write_animated_png({a}, dir / "long.png", 65536), std::invalid_argument);
  CHECK_NOTHROW(kerf::write_animated_png({a}, dir / "one.png", 65535));
}
