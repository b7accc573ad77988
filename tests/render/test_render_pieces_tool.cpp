// The picture tool examples/render_pieces.cpp from the command line: a picture of the size
// asked for, and for bad input one line naming the file (or the option) and a non-zero status.
#include "two_pieces.hpp"

#include "support/run_program.hpp"

#include <doctest/doctest.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <algorithm>
#include <string>

namespace {

const std::string tool = std::string(KERF_BINARY_DIR) + "/bin/render_pieces";

/// A path in single quotes, for the shell. (Built by appending: GCC 12 warns falsely about
/// `"literal" + std::string` at -O2.)
std::string quoted(const std::filesystem::path& file) {
  std::string text(1, '\'');
  text += file.string();
  text += '\'';
  return text;
}

kerf_test::ProgramResult render(const std::string& arguments, const std::filesystem::path& work) {
  return kerf_test::run_program(tool + " " + arguments, work);
}

} // namespace

TEST_CASE("render_pieces draws a PNG of the size asked for") {
  const auto work = kerf_test::fresh_dir("tool_png");
  render_test::write_two_pieces(work / "pieces.vtu", 0.3);
  const auto result = render(quoted(work / "pieces.vtu") + " " + quoted(work / "out/open.png") +
                                 " --warp 2 --color piece --azimuth 0 --elevation 0 --size 160x120",
                             work);
  REQUIRE(result.exit_status == 0);
  CHECK(result.out.find("wrote ") != std::string::npos);
  vtkNew<vtkPNGReader> png;
  png->SetFileName((work / "out/open.png").string().c_str());
  png->Update();
  CHECK(png->GetOutput()->GetDimensions()[0] == 160);
  CHECK(png->GetOutput()->GetDimensions()[1] == 120);
  CHECK(render_test::drawn_fraction(*png->GetOutput()) > 0.05);
  // The open cut is in the saved file too: background between the pieces up the middle column.
  CHECK(render_test::scan_column(*png->GetOutput(), 80).background_between > 0);
}

TEST_CASE("render_pieces draws several inputs side by side under one camera") {
  // The slabs seen from y < 0 (x to the right, z up), unmoved: one copy fills its part of the
  // middle row without a gap; two, the second moved 0.5 m along x (the slabs are 0.1 m wide in
  // x), leave background between them on that row, and the picture is still one camera's.
  const auto work = kerf_test::fresh_dir("tool_strip");
  render_test::write_two_pieces(work / "pieces.vtu", 0.3);
  const std::string in = quoted(work / "pieces.vtu");
  const std::string options = " --warp 0 --azimuth -90 --elevation 0 --size 400x240";
  REQUIRE(render(in + " " + quoted(work / "one.png") + options, work).exit_status == 0);
  REQUIRE(render(in + " " + in + " " + quoted(work / "two.png") + options + " --spacing 0.5", work).exit_status == 0);
  vtkNew<vtkPNGReader> one, two;
  one->SetFileName((work / "one.png").string().c_str());
  one->Update();
  two->SetFileName((work / "two.png").string().c_str());
  two->Update();
  const render_test::ScanLine single = render_test::scan_row(*one->GetOutput(), 120), strip = render_test::scan_row(*two->GetOutput(), 120);
  REQUIRE(single.first >= 0);
  REQUIRE(strip.first >= 0);
  CHECK(single.background_between == 0);
  // The gap is 0.4 m of the 0.6 m between the first and the last drawn pixel; the slabs' side
  // faces, seen in perspective (they are 1 m deep), cover part of it: a third is still a gap
  // that the single picture does not have.
  CHECK(strip.background_between > (strip.last - strip.first) / 3);
}

TEST_CASE("render_pieces --help prints its usage and exits 0") {
  const auto result = render("--help", kerf_test::fresh_dir("tool_help"));
  CHECK(result.exit_status == 0);
  CHECK(result.out.find("usage: render_pieces IN.vtu OUT.png") == 0);
}

TEST_CASE("render_pieces refuses bad input with one line naming the file or the option") {
  const auto work = kerf_test::fresh_dir("tool_errors");
  const std::string png = quoted(work / "out.png");
  const auto expect_error = [&](const std::string& arguments, const std::string& message) {
    const auto result = render(arguments, work);
    CHECK(result.exit_status == 2);
    CHECK_MESSAGE(result.err.find(message) != std::string::npos, result.err);
    CHECK(std::count(result.err.begin(), result.err.end(), '\n') == 1);
    CHECK(!std::filesystem::exists(work / "out.png"));
  };

  SUBCASE("a missing file") {
    const auto missing = work / "missing.vtu";
    expect_error(quoted(missing) + " " + png, std::string("render_pieces: error: ") += missing.string() + ": file: does not exist");
  }
  SUBCASE("a .vtu without a displacement") {
    const auto still = work / "still.vtu";
    kerf::write_vtu(still, kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {1, 1, 1}), {}, {});
    expect_error(quoted(still) + " " + png, still.string() + ": displacement: no point array 'displacement'");
  }
  SUBCASE("a file that is no VTK XML file") {
    const auto text = work / "text.vtu";
    kerf_test::write_text(text, "this is not a mesh\n");
    expect_error(quoted(text) + " " + png, std::string("render_pieces: error: ") += text.string() + ": ");
  }
  SUBCASE("a colour array the file does not have") {
    const auto pieces = work / "pieces.vtu";
    render_test::write_two_pieces(pieces, 0.3);
    expect_error(quoted(pieces) + " " + png + " --color side",
                 pieces.string() + ": side: no cell array of that name (the file has: piece)");
  }
  SUBCASE("bad options") {
    const auto pieces = work / "pieces.vtu";
    render_test::write_two_pieces(pieces, 0.3);
    const std::string in = quoted(pieces) + " " + png;
    expect_error(in + " --size 0x10", "command line: --size: expected WxH");
    expect_error(in + " --warp fast", "command line: --warp: expected a number, found 'fast'");
    expect_error(in + " --elevation 90", "command line: --elevation: expected an angle in (-90, 90)");
    expect_error(in + " --clip-plane 0,0,0,1", "command line: --clip-plane: expected six numbers");
    expect_error(in + " --clip-plane 0,0,0,0,0,0", "command line: --clip-plane: the normal (nx,ny,nz) is zero");
    expect_error(in + " --clip-plane 0,0,5,0,0,1", "command line: --clip-plane: the plane leaves nothing of the body");
    expect_error(in + " --azimuth", "command line: --azimuth: expected a value after it");
    expect_error(in + " --shadows", "command line: --shadows: unknown option");
    expect_error(png, "command line: files: expected IN.vtu OUT.png");
  }
  SUBCASE("no X display") {
    const auto pieces = work / "pieces.vtu";
    render_test::write_two_pieces(pieces, 0.3);
    const auto result = kerf_test::run_program(std::string("env -u DISPLAY ") += tool + " " + quoted(pieces) + " " + png, work);
    CHECK(result.exit_status == 2);
    CHECK(result.err == "render_pieces: error: environment: DISPLAY: no X display to draw on (VTK 9.1 draws through X): run under xvfb-run -a\n");
  }
}
