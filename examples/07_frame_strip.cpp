// 07_frame_strip: PNG frames of one size side by side in one PNG, for a figure of a run.
//
//   07_frame_strip OUT.png FRAME.png [FRAME.png ...] [--shrink n]
//
// Chapter 7's program draws its frames itself (a fixed camera, render/organ_view.hpp), so a
// strip of them needs no renderer, only the pixels: every frame is read, cropped to the box of
// pixels that differ from the background in any frame (plus a margin, the same box for all, so
// that the frames keep one scale and the organ's motion shows), shrunk by averaging n x n
// blocks, and laid left to right with a white gap between (figures/07_liver/frame_strip.sh).
// It reads and writes files and draws nothing, so it needs no display.
#include "kerf/app/command_line.hpp"
#include "kerf/app/input_error.hpp"
#include "kerf/render/surface_image.hpp"
#include "kerf/render/write_png.hpp"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace {

const std::string usage =
    "usage: 07_frame_strip OUT.png FRAME.png [FRAME.png ...] [--shrink n]\n"
    "Lays PNG frames of one size (RGB, as 07_liver writes them) side by side into OUT.png: each cropped to the\n"
    "box of non-background pixels of all frames, shrunk n times (default 2) by averaging, 8 white pixels apart.\n";

constexpr int margin = 12; // pixels kept around the drawn box, before shrinking
constexpr int gap = 8;     // white pixels between two frames, after shrinking

/// An RGB frame read from a PNG file.
vtkSmartPointer<vtkImageData> read_frame(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file)) throw kerf::InputError(file.string(), "file", "no such file");
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(file.string().c_str())) throw kerf::InputError(file.string(), "PNG", "not a PNG file");
  reader->SetFileName(file.string().c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  if (image->GetNumberOfScalarComponents() != 3 || image->GetScalarType() != VTK_UNSIGNED_CHAR)
    throw kerf::InputError(file.string(), "PNG", "expected 8-bit RGB pixels");
  vtkSmartPointer<vtkImageData> copy = vtkSmartPointer<vtkImageData>::New();
  copy->DeepCopy(image);
  return copy;
}

const unsigned char* pixel(vtkImageData& image, int x, int y) {
  return static_cast<const unsigned char*>(image.GetScalarPointer(x, y, 0));
}

void run(int argc, char** argv) {
  std::vector<std::filesystem::path> files;
  int shrink = 2;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help") {
      std::cout << usage;
      return;
    }
    if (arg == "--shrink") {
      if (i + 1 >= argc) throw kerf::InputError("command line", "--shrink", "expected a whole number after it");
      try {
        shrink = std::stoi(argv[++i]);
      } catch (const std::exception&) {
        shrink = 0;
      }
      if (shrink < 1 || shrink > 16) throw kerf::InputError("command line", "--shrink", "expected a whole number in [1, 16]");
    } else {
      files.emplace_back(arg);
    }
  }
  if (files.size() < 2) throw kerf::InputError("command line", "arguments", "expected OUT.png and at least one frame (see --help)");
  const std::filesystem::path out = files.front();
  files.erase(files.begin());

  std::vector<vtkSmartPointer<vtkImageData>> frames;
  for (const auto& file : files) frames.push_back(read_frame(file));
  int dims[3];
  frames.front()->GetDimensions(dims);
  const int width = dims[0], height = dims[1];
  for (std::size_t f = 1; f < frames.size(); ++f) {
    int other[3];
    frames[f]->GetDimensions(other);
    if (other[0] != width || other[1] != height)
      throw kerf::InputError(files[f].string(), "PNG", "its size differs from the first frame's (" + std::to_string(width) + " x " +
                                                           std::to_string(height) + ")");
  }

  // The box of drawn pixels over all frames: what is not the pictures' white background.
  const auto& white = kerf::picture_background;
  int x0 = width, y0 = height, x1 = -1, y1 = -1;
  for (const auto& frame : frames)
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const unsigned char* p = pixel(*frame, x, y);
        if (p[0] == white[0] && p[1] == white[1] && p[2] == white[2]) continue;
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
      }
  if (x1 < 0) { // all white: keep everything
    x0 = y0 = 0;
    x1 = width - 1;
    y1 = height - 1;
  }
  x0 = std::max(0, x0 - margin);
  y0 = std::max(0, y0 - margin);
  x1 = std::min(width - 1, x1 + margin);
  y1 = std::min(height - 1, y1 + margin);
  const int cell_w = (x1 - x0 + 1) / shrink, cell_h = (y1 - y0 + 1) / shrink;
  const int n = static_cast<int>(frames.size());

  vtkNew<vtkImageData> strip;
  strip->SetDimensions(n * cell_w + (n - 1) * gap, cell_h, 1);
  strip->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* out_pixels = static_cast<unsigned char*>(strip->GetScalarPointer());
  const int strip_w = n * cell_w + (n - 1) * gap;
  for (int k = 0; k < strip_w * cell_h; ++k) std::copy(white.begin(), white.end(), out_pixels + 3 * k);
  for (int f = 0; f < n; ++f)
    for (int y = 0; y < cell_h; ++y)
      for (int x = 0; x < cell_w; ++x) {
        std::array<int, 3> sum{0, 0, 0};
        for (int dy = 0; dy < shrink; ++dy)
          for (int dx = 0; dx < shrink; ++dx) {
            const unsigned char* p = pixel(*frames[static_cast<std::size_t>(f)], x0 + shrink * x + dx, y0 + shrink * y + dy);
            for (int c = 0; c < 3; ++c) sum[static_cast<std::size_t>(c)] += p[c];
          }
        unsigned char* q = out_pixels + 3 * (y * strip_w + f * (cell_w + gap) + x);
        for (int c = 0; c < 3; ++c) q[c] = static_cast<unsigned char>((sum[static_cast<std::size_t>(c)] + shrink * shrink / 2) / (shrink * shrink));
      }
  kerf::write_png(out, *strip);
  std::cout << "wrote " << out.string() << ": " << n << " frames of " << cell_w << " x " << cell_h << " pixels (cropped from " << width
            << " x " << height << ", shrunk " << shrink << " times)\n";
}

} // namespace

int main(int argc, char** argv) {
  return kerf::run_reporting_errors("07_frame_strip", [&] { run(argc, argv); });
}
