// render_pieces: a picture of a body Kerf wrote, moved by its displacement, as a PNG file.
//
//   render_pieces IN.vtu [IN2.vtu ...] OUT.png [--warp s] [--color displacement|CELL_ARRAY]
//                 [--azimuth a] [--elevation e] [--zoom z] [--size WxH] [--clip-plane ox,oy,oz,nx,ny,nz]
//                 [--spacing dx]
//
// With several inputs (the frames of a run) it draws a strip: every body in one picture, the
// k-th moved by k dx along x, under one camera, so that the frames share one scale
// (figures/06_newmark/render_strip.sh).
//
// The figure scripts use it (figures/04_cut_quadrature/render_open_cut.sh draws chapter 4's
// open cut from the demo's beam_curved_cut_pieces.vtu). It draws through X: on a machine
// without a screen run it as `xvfb-run -a render_pieces ...`. The steps are the render area's
// headers, one each: read the pieces, move them and take their surface, draw, save.
#include "kerf/app/command_line.hpp"
#include "kerf/app/input_error.hpp"
#include "kerf/render/piece_mesh.hpp"
#include "kerf/render/surface_image.hpp"
#include "kerf/render/warped_surface.hpp"
#include "kerf/render/write_png.hpp"

#include <vtkAppendPolyData.h>
#include <vtkNew.h>
#include <vtkPoints.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace {

const std::string usage =
    "usage: render_pieces IN.vtu OUT.png [--warp s] [--color displacement|CELL_ARRAY] [--azimuth a]\n"
    "                     [--elevation e] [--zoom z] [--size WxH] [--clip-plane ox,oy,oz,nx,ny,nz]\n"
    "       render_pieces IN.vtu IN2.vtu ... OUT.png [the same options] [--spacing dx]    (a strip)\n"
    "Draws the body in IN.vtu (a .vtu a Kerf program wrote, with the point array 'displacement'), every point\n"
    "moved by s times its displacement, into the picture OUT.png. Needs an X display: xvfb-run -a render_pieces ...\n"
    "  --warp s          factor on the displacement (default 1: as it moved; 0: unmoved)\n"
    "  --color NAME      'displacement' (default): |u| per point; or a cell array of IN.vtu, such as 'piece'\n"
    "                    in the XFEM view of a cut body (-1 for a tet drawn whole, 0, 1, ... for the pieces)\n"
    "  --azimuth a       the camera's direction in the x-y plane, degrees from +x towards +y (default -135)\n"
    "  --elevation e     the camera's height above the x-y plane, degrees in (-90, 90) (default 20); z is up\n"
    "  --zoom z          closer (> 1) or farther (< 1) than the distance at which the body fits (default 1)\n"
    "  --size WxH        the picture's size in pixels (default 1200x900)\n"
    "  --clip-plane o,n  six numbers: draw only the part of the moved body on the side the normal n points to\n"
    "                    of the plane through o, cut open along the plane (coordinates in metres)\n"
    "  --spacing dx      with several IN files: the k-th drawn moved by k dx along x (m; default 1.25 times the\n"
    "                    widest body's x extent), all under one camera\n"
    "  --help            this text\n";

/// What the command line asked for.
struct Request {
  std::vector<std::filesystem::path> in;
  std::filesystem::path out;
  std::optional<double> spacing;
  double warp = 1.0;
  std::optional<kerf::ClipPlane> clip;
  kerf::PictureSettings picture;
  bool help = false;
};

/// The numbers of a comma-separated list, all finite; an InputError naming the option otherwise.
std::vector<double> parse_numbers(const std::string& option, const std::string& text, char separator) {
  std::vector<double> numbers;
  std::string_view rest = text;
  while (true) {
    const std::string_view item = rest.substr(0, rest.find(separator));
    double value = 0;
    const auto [end, error] = std::from_chars(item.data(), item.data() + item.size(), value);
    if (item.empty() || error != std::errc() || end != item.data() + item.size() || !std::isfinite(value))
      throw kerf::InputError("command line", option, "expected a number, found '" + std::string(item) + "'");
    numbers.push_back(value);
    if (item.size() == rest.size()) return numbers;
    rest.remove_prefix(item.size() + 1);
  }
}

double parse_number(const std::string& option, const std::string& text) {
  const std::vector<double> numbers = parse_numbers(option, text, ',');
  if (numbers.size() != 1) throw kerf::InputError("command line", option, "expected one number, found '" + text + "'");
  return numbers[0];
}

Request parse_request(int argc, char** argv) {
  Request request;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw kerf::InputError("command line", arg, "expected a value after it");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") request.help = true;
    else if (arg == "--warp") request.warp = parse_number(arg, value());
    else if (arg == "--color") request.picture.colour_by = value();
    else if (arg == "--azimuth") request.picture.camera.azimuth = parse_number(arg, value());
    else if (arg == "--elevation") request.picture.camera.elevation = parse_number(arg, value());
    else if (arg == "--zoom") request.picture.camera.zoom = parse_number(arg, value());
    else if (arg == "--size") {
      const std::string size = value();
      const std::vector<double> wh = parse_numbers(arg, size, 'x');
      if (wh.size() != 2 || wh[0] != std::round(wh[0]) || wh[1] != std::round(wh[1]) || wh[0] < 1 || wh[1] < 1 ||
          wh[0] > 8192 || wh[1] > 8192)
        throw kerf::InputError("command line", arg, "expected WxH, two whole numbers of pixels from 1 to 8192, found '" + size + "'");
      request.picture.width = static_cast<int>(wh[0]);
      request.picture.height = static_cast<int>(wh[1]);
    } else if (arg == "--clip-plane") {
      const std::string plane = value();
      const std::vector<double> p = parse_numbers(arg, plane, ',');
      if (p.size() != 6) throw kerf::InputError("command line", arg, "expected six numbers ox,oy,oz,nx,ny,nz, found '" + plane + "'");
      const kerf::ClipPlane clip{{p[0], p[1], p[2]}, {p[3], p[4], p[5]}};
      if (clip.normal.norm() == 0.0) throw kerf::InputError("command line", arg, "the normal (nx,ny,nz) is zero");
      request.clip = clip;
    } else if (arg == "--spacing") {
      request.spacing = parse_number(arg, value());
      if (!(*request.spacing > 0.0)) throw kerf::InputError("command line", arg, "expected a positive distance in m");
    } else if (arg.starts_with("--")) throw kerf::InputError("command line", arg, "unknown option (see --help)");
    else files.push_back(arg);
  }
  if (request.help) return request;
  if (files.size() < 2) throw kerf::InputError("command line", "files", "expected IN.vtu OUT.png, or IN.vtu IN2.vtu ... OUT.png for a strip (see --help)");
  if (!(std::abs(request.picture.camera.elevation) < 90.0))
    throw kerf::InputError("command line", "--elevation", "expected an angle in (-90, 90) degrees, z being up");
  if (!(request.picture.camera.zoom > 0.0)) throw kerf::InputError("command line", "--zoom", "expected a positive factor");
  request.in.assign(files.begin(), files.end() - 1);
  request.out = files.back();
  return request;
}

} // namespace

int main(int argc, char** argv) {
  return kerf::run_reporting_errors("render_pieces", [&] {
    const Request request = parse_request(argc, argv);
    if (request.help) {
      std::cout << usage;
      return;
    }
    std::vector<vtkSmartPointer<vtkPolyData>> surfaces;
    double widest = 0.0;
    for (const std::filesystem::path& in : request.in) {
      const vtkSmartPointer<vtkUnstructuredGrid> body = kerf::read_piece_mesh(in);
      if (request.picture.colour_by != "displacement") kerf::require_cell_array(*body, request.picture.colour_by, in);
      surfaces.push_back(kerf::warped_surface(*body, request.warp, request.clip));
      if (surfaces.back()->GetNumberOfPolys() == 0)
        throw kerf::InputError("command line", "--clip-plane", "the plane leaves nothing of the body in " + in.string());
      const double* bounds = surfaces.back()->GetBounds();
      widest = std::max(widest, bounds[1] - bounds[0]);
    }
    // The strip: the k-th surface moved by k dx along x, all appended into one surface, which
    // one camera then fits (a single input is drawn as it is).
    const double dx = request.spacing.value_or(1.25 * widest);
    vtkNew<vtkAppendPolyData> strip;
    for (std::size_t k = 0; k < surfaces.size(); ++k) {
      vtkPoints* points = surfaces[k]->GetPoints();
      for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i) {
        double x[3];
        points->GetPoint(i, x);
        x[0] += double(k) * dx;
        points->SetPoint(i, x);
      }
      strip->AddInputData(surfaces[k]);
    }
    strip->Update();
    const vtkSmartPointer<vtkPolyData> surface = strip->GetOutput();
    const vtkSmartPointer<vtkImageData> image = kerf::render_surface_image(*surface, request.picture);
    kerf::write_png(request.out, *image);
    std::cout << "wrote " << request.out.string() << " (" << request.picture.width << " x " << request.picture.height << ")\n";
  });
}
