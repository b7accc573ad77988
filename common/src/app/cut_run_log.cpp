#include "kerf/app/cut_run_log.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/io/animated_png.hpp"
#include "kerf/io/probes_csv.hpp"
#include "kerf/io/write_vtu.hpp"
#include "kerf/xfem/cut_xfem_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace kerf {

std::ofstream open_csv(const std::filesystem::path& path, const char* header) {
  std::ofstream file(path);
  if (!file) throw InputError(path.string(), "write", "cannot open the file");
  file << header;
  return file;
}

CutRunLog::CutRunLog(CutRunLogSettings settings, const PointLocator& locator) : settings_(std::move(settings)), locator_(locator) {
  std::filesystem::create_directories(settings_.out_dir);
  energy_csv_ = open_csv(settings_.out_dir / "energy.csv", energy_csv_header);
  opening_csv_ = open_csv(settings_.out_dir / "opening.csv", "step,t,cut_area,gap_volume,mean_opening,max_opening,max_jump\n");
  if (settings_.probes_history) {
    probe_points_ = read_probes_csv(*settings_.probes_in);
    history_csv_ = open_csv(*settings_.probes_history, "step,t,probe,ux,uy,uz\n");
  }
}

std::vector<std::string> write_run_animation(const std::vector<std::filesystem::path>& frames, const Scene& scene,
                                             const std::filesystem::path& out_dir) {
  if (frames.empty()) return {};
  std::vector<std::string> lines{"wrote " + std::to_string(frames.size()) + " PNG frames in " + (out_dir / "frames").string()};
  if (!scene.render.animation) return lines;
  const std::filesystem::path film = out_dir / (scene.name + ".png");
  const int delay = std::clamp(static_cast<int>(std::lround(1000.0 * scene.render.every * scene.time.dt)), 1, 65535);
  write_animated_png(frames, film, delay);
  lines.push_back("wrote " + film.string() + " (animated PNG, " + std::to_string(frames.size()) + " frames)");
  return lines;
}

std::filesystem::path CutRunLog::pvd() const { return settings_.out_dir / (settings_.name + "_pieces.pvd"); }

void CutRunLog::write(int step, double t, const CutXfemModel& model, const CutSurfaces& cuts, const Eigen::VectorXd& u,
                      const EnergyAccount& account) {
  write_energy_row(energy_csv_, step, t, account);
  if (history_csv_.is_open()) {
    Eigen::Index outside = 0;
    const TetField field = [&](Eigen::Index tet, const Eigen::Vector3d& x) { return model.displacement_at(u, tet, x); };
    const Eigen::MatrixXd values = evaluate_tet_field_at(model.mesh(), field, probe_points_, outside);
    write_probe_history_rows(history_csv_, step, t, values);
    if (step == 0 && outside > 0) std::cerr << "warning: " << outside << " probes lie outside the mesh; their history is nan\n";
  }
  if (!opening_) {
    const double spacing = 0.5 * settings_.mean_edge;
    if (!sample_points_) sample_points_.emplace(locator_, spacing, 2e-6 * spacing);
    sample_points_->update(cuts.surfaces());
    opening_ = std::make_unique<CutOpeningSampler>(model, *sample_points_);
  }
  const CutOpening opening = opening_->measure(u);
  char row[512];
  std::snprintf(row, sizeof row, "%d,%.17g,%.9e,%.9e,%.9e,%.9e,%.9e\n", step, t, opening.area, opening.gap_volume, opening.mean_opening(),
                opening.max_normal_opening, opening.max_jump);
  opening_csv_ << row;
  if (step % settings_.output_every == 0 || step == settings_.last_step) {
    char name[64];
    std::snprintf(name, sizeof name, "_pieces_%06d.vtu", step);
    const std::filesystem::path frame = settings_.out_dir / (settings_.name + name);
    write_cut_xfem_vtu(frame, model, u);
    frames_.emplace_back(t, frame);
    write_pvd(pvd(), frames_);
  }
}

} // namespace kerf
