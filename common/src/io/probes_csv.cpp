#include "kerf/io/probes_csv.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/fem/evaluate_displacement.hpp"
#include "kerf/mesh/number_table_csv.hpp"
#include "kerf/mesh/point_locator.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace kerf {

Eigen::MatrixXd read_probes_csv(const std::filesystem::path& file) { return read_number_table_csv(file, "x,y,z", "probe file"); }

void write_probes_csv(const std::filesystem::path& file, const Eigen::MatrixXd& points, const Eigen::MatrixXd& displacements) {
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  std::FILE* out = std::fopen(file.string().c_str(), "w");
  if (!out) throw InputError(file.string(), "file", "cannot write the probe output");
  std::fprintf(out, "x,y,z,ux,uy,uz\n");
  for (Eigen::Index p = 0; p < points.rows(); ++p) {
    for (int c = 0; c < 3; ++c) std::fprintf(out, "%.17g,", points(p, c));
    for (int c = 0; c < 3; ++c) {
      const double v = displacements(p, c);
      if (std::isnan(v)) std::fprintf(out, "nan");
      else std::fprintf(out, "%.17g", v);
      std::fprintf(out, c < 2 ? "," : "\n");
    }
  }
  if (std::fclose(out) != 0) throw InputError(file.string(), "file", "cannot write the probe output");
}

Eigen::MatrixXd evaluate_tet_field_at(const TetMesh& mesh, const TetField& field, const Eigen::MatrixXd& points,
                                      Eigen::Index& num_outside) {
  const PointLocator locator(mesh);
  Eigen::MatrixXd values(points.rows(), 3);
  num_outside = 0;
  for (Eigen::Index p = 0; p < points.rows(); ++p) {
    const Eigen::Vector3d x = points.row(p).transpose();
    const PointLocation location = locator.locate(x);
    if (location.tet < 0) {
      values.row(p).setConstant(std::numeric_limits<double>::quiet_NaN());
      ++num_outside;
      continue;
    }
    values.row(p) = field(location.tet, x).transpose();
  }
  return values;
}

void sample_tet_field_probes(const std::filesystem::path& probes_in, const std::filesystem::path& probes_out,
                             const TetMesh& mesh, const TetField& field, std::ostream* warnings) {
  const Eigen::MatrixXd points = read_probes_csv(probes_in);
  Eigen::Index num_outside = 0;
  const Eigen::MatrixXd values = evaluate_tet_field_at(mesh, field, points, num_outside);
  if (num_outside > 0 && warnings)
    *warnings << "warning: " << probes_in.string() << ": " << num_outside << " of " << points.rows()
              << " probe points lie outside the mesh; their displacement is written as nan\n";
  write_probes_csv(probes_out, points, values);
}

void sample_probes(const std::filesystem::path& probes_in, const std::filesystem::path& probes_out, const TetMesh& mesh,
                   const Eigen::VectorXd& u, std::ostream* warnings) {
  const Eigen::MatrixXd points = read_probes_csv(probes_in);
  Eigen::Index num_outside = 0;
  const Eigen::MatrixXd values = evaluate_displacement_at(mesh, u, points, num_outside);
  write_probes_csv(probes_out, points, values);
  if (num_outside > 0 && warnings)
    *warnings << "warning: " << probes_in.string() << ": " << num_outside << " of " << points.rows()
              << " probe points are outside the mesh (written as nan)\n";
}

void write_probe_history_rows(std::ostream& out, int step, double t, const Eigen::MatrixXd& values) {
  char row[256];
  for (Eigen::Index p = 0; p < values.rows(); ++p) {
    std::snprintf(row, sizeof row, "%d,%.17g,%ld,%.17g,%.17g,%.17g\n", step, t, static_cast<long>(p), values(p, 0), values(p, 1), values(p, 2));
    out << row;
  }
}

} // namespace kerf
