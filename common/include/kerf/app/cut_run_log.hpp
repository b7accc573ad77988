/// @file cut_run_log.hpp
/// @brief The files a cutting program writes as it steps: energy.csv, opening.csv, the probes' history and the .pvd series of the pieces.
///
/// energy.csv (the energy account, dynamics/energy_account.hpp) and opening.csv (how far the wound
/// has opened, xfem/cut_opening.hpp) get a row every step, the probes' history too when asked
/// for; the pieces go into the .pvd series every output.every steps and at the last step. The
/// opening is the jump across the cut, sampled every half edge from points 2e-6 of an edge
/// either side of it: where the points lie is found once per cut triangle, their weights once per
/// model (model_changed drops them), the jump at every step.
#pragma once

#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/dynamics/energy_account.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/scene/scene.hpp"
#include "kerf/xfem/cut_opening.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace kerf {

/// Where and how often.
struct CutRunLogSettings {
  std::filesystem::path out_dir;          ///< created if missing
  std::string name;                       ///< the scene's: NAME_pieces.pvd, NAME_pieces_NNNNNN.vtu
  int output_every = 1;                   ///< a .vtu every n steps
  int last_step = 0;                      ///< and at this one
  double mean_edge = 0.0;                 ///< the mesh's (m): the opening's samples are half of it apart
  std::optional<std::filesystem::path> probes_in;      ///< points (x,y,z) whose displacement ...
  std::optional<std::filesystem::path> probes_history; ///< ... is written here every step
};

/// The run's files, open from construction to destruction.
class CutRunLog {
public:
  /// @param locator a point locator of the reference mesh (kept by reference)
  /// @throws InputError naming a file that cannot be opened
  CutRunLog(CutRunLogSettings settings, const PointLocator& locator);
  /// The model is about to change: the opening's weights, found in its pieces, go.
  void model_changed() { opening_.reset(); }
  /// Step `step`'s rows (and .vtu): the body `model` cut by `cuts`, displaced by `u`.
  void write(int step, double t, const CutXfemModel& model, const CutSurfaces& cuts, const Eigen::VectorXd& u, const EnergyAccount& account);
  /// The .pvd series and how many frames it has.
  std::filesystem::path pvd() const;
  std::size_t num_frames() const { return frames_.size(); }

private:
  CutRunLogSettings settings_;
  const PointLocator& locator_;
  std::ofstream energy_csv_, opening_csv_, history_csv_;
  Eigen::MatrixXd probe_points_;
  std::optional<CutSamplePoints> sample_points_;
  std::unique_ptr<CutOpeningSampler> opening_;
  std::vector<std::pair<double, std::filesystem::path>> frames_;
};

/// A run's PNG frames (none: nothing) and, if the scene's render.animation, the animated PNG of
/// them, OUT_DIR/NAME.png (NAME the scene's), played at the simulation's pace (a frame every render.every
/// steps of dt). Returns what to report: a line per file written.
std::vector<std::string> write_run_animation(const std::vector<std::filesystem::path>& frames, const Scene& scene,
                                             const std::filesystem::path& out_dir);

/// Opens `path` for writing with its CSV header.
/// @throws InputError `path: write: cannot open the file`
std::ofstream open_csv(const std::filesystem::path& path, const char* header);

} // namespace kerf
