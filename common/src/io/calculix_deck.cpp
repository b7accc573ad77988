#include "kerf/io/calculix_deck.hpp"

#include <Eigen/SparseCholesky>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>

namespace kerf {

namespace {

/// Quotes a string for /bin/sh: inside single quotes only the quote itself needs care.
std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// The string without leading and trailing blanks (ccx pads its messages to 132 columns).
std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

/// Parses one number of a Fortran E format. Fortran drops the 'E' when the exponent has three
/// digits ("0.123456-100"), which strtod would read as 0.123456, so the 'E' is put back.
double parse_fortran_double(std::string token) {
  const auto sign = token.find_first_of("+-", 1);
  if (sign != std::string::npos && token.find_first_of("eEdD") == std::string::npos) token.insert(sign, "E");
  for (char& c : token)
    if (c == 'd' || c == 'D') c = 'E';
  std::size_t used = 0;
  const double value = std::stod(token, &used);
  if (used != token.size()) throw std::runtime_error("not a number: " + token);
  return value;
}

/// Reads a symmetric matrix stored as "row column value" lines, 1-based, one triangle only.
Eigen::SparseMatrix<double> read_triangle_file(const std::filesystem::path& file, Eigen::Index n) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("read_calculix_matrices: cannot open " + file.string());
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::Index i = 0, j = 0;
  std::string value;
  while (in >> i >> j >> value) {
    if (i < 1 || j < 1 || i > n || j > n)
      throw std::runtime_error("read_calculix_matrices: index out of range in " + file.string());
    const double a = parse_fortran_double(value);
    triplets.emplace_back(i - 1, j - 1, a);
    if (i != j) triplets.emplace_back(j - 1, i - 1, a); // ccx stores one triangle of a symmetric matrix
  }
  if (!in.eof()) throw std::runtime_error("read_calculix_matrices: malformed line in " + file.string());
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(triplets.begin(), triplets.end());
  return a;
}

/// Writes a double as precisely as a CalculiX field holds it. 17 significant digits round-trip
/// any double exactly, but ccx reads at most 20 characters per number and silently cuts a longer
/// one ("-1.2345678901234567e-05" loses its exponent), so we take the most digits that fit in
/// 20 characters: 17 for most coordinates, 14 in the worst case (a negative number with a
/// three-character exponent), a relative rounding of at most 5e-15.
std::string exact(double x) {
  for (int digits = 17; digits > 1; --digits) {
    std::ostringstream s;
    s.precision(digits);
    s << x;
    if (s.str().size() <= 20) return s.str();
  }
  return std::to_string(x);
}

} // namespace

void write_calculix_deck(const std::filesystem::path& inp, const TetMesh& mesh, const CalculixJob& job) {
  const Eigen::Index nv = mesh.num_nodes();
  if (mesh.nodes_per_tet() != 4 && mesh.nodes_per_tet() != 10)
    throw std::invalid_argument("write_calculix_deck: the mesh must be Tet4 or Tet10");
  if (job.nodal_loads.size() != 0 && job.nodal_loads.size() != 3 * nv)
    throw std::invalid_argument("write_calculix_deck: nodal_loads must be empty or of size 3#V");
  const bool matrices = job.procedure == CalculixProcedure::matrix_storage;
  if (matrices && job.nlgeom)
    throw std::invalid_argument("write_calculix_deck: NLGEOM is for the static route only");
  if (job.nlgeom && !(job.min_increment > 0.0 && job.min_increment <= job.initial_increment &&
                      job.initial_increment <= job.max_increment && job.max_increment <= 1.0 && job.max_increments > 0))
    throw std::invalid_argument("write_calculix_deck: NLGEOM needs 0 < min <= initial <= max <= 1 increments");
  if (matrices && !(job.material.density > 0.0))
    throw std::invalid_argument("write_calculix_deck: the matrix route needs a positive density (M g)");
  const bool frequency = job.procedure == CalculixProcedure::frequency;
  if (frequency && (!(job.material.density > 0.0) || job.frequencies < 1 || job.nlgeom || job.gravity.norm() > 0.0 ||
                    job.nodal_loads.size() != 0 || !job.face_pressures.empty()))
    throw std::invalid_argument("write_calculix_deck: the frequency route needs a positive density, frequencies >= 1 and no loads");

  std::ofstream out(inp);
  if (!out) throw std::runtime_error("write_calculix_deck: cannot write " + inp.string());
  out << "** Written by Kerf (kerf::write_calculix_deck). Kerf node v is node v+1, tet t is element t+1.\n";
  out << "*NODE, NSET=NALL\n";
  for (Eigen::Index v = 0; v < nv; ++v)
    out << v + 1 << ", " << exact(mesh.nodes(v, 0)) << ", " << exact(mesh.nodes(v, 1)) << ", "
        << exact(mesh.nodes(v, 2)) << "\n";
  // Kerf's Tet10 order is VTK's, which is also C3D10's, so the connectivity is copied as is.
  out << "*ELEMENT, TYPE=" << (mesh.nodes_per_tet() == 4 ? "C3D4" : "C3D10") << ", ELSET=EALL\n";
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    out << t + 1;
    for (int k = 0; k < mesh.nodes_per_tet(); ++k) out << ", " << mesh.tets(t, k) + 1;
    out << "\n";
  }
  out << "*MATERIAL, NAME=KERF\n*ELASTIC\n"
      << exact(job.material.young) << ", " << exact(job.material.poisson) << "\n";
  if (job.material.density > 0.0) out << "*DENSITY\n" << exact(job.material.density) << "\n";
  out << "*SOLID SECTION, ELSET=EALL, MATERIAL=KERF\n";

  if (matrices) {
    // No *BOUNDARY: ccx then stores K and M over every DOF, and the gravity load M g sums
    // over all columns, constrained ones included (the .mas of a constrained model lacks them).
    // MATRIXSTORAGE writes .sti, .mas, .dof and stops before any eigenvalue solve, so the
    // singular unconstrained K does no harm; it takes no data line (a "1" draws a warning).
    out << "*STEP\n*FREQUENCY, SOLVER=MATRIXSTORAGE\n*END STEP\n";
    return;
  }

  if (job.nlgeom) {
    // Geometrically nonlinear: the loads are ramped from 0 to 1 over automatic increments of
    // at most max_increment, and each increment is solved by Newton's method. ccx rejects the
    // 17-digit form of these numbers on this card, so they are written with 6 digits.
    std::ostringstream increments;
    increments << job.initial_increment << ", 1, " << job.min_increment << ", " << job.max_increment;
    out << "*STEP, NLGEOM, INC=" << job.max_increments << "\n*STATIC\n" << increments.str() << "\n";
  } else if (frequency) {
    out << "*STEP\n*FREQUENCY\n" << job.frequencies << "\n";
  } else {
    out << "*STEP\n*STATIC\n";
  }
  const DofMap dofs = make_dof_map(nv, job.dirichlet);
  bool any = false;
  for (Eigen::Index d = 0; d < 3 * nv; ++d) {
    if (dofs.free_index[static_cast<std::size_t>(d)] >= 0) continue;
    if (!any) out << "*BOUNDARY\n";
    any = true;
    out << d / 3 + 1 << ", " << d % 3 + 1 << ", " << d % 3 + 1 << ", " << exact(dofs.prescribed[d]) << "\n";
  }
  if (frequency) {
    out << "*END STEP\n"; // the eigenvalues go to the .dat without a print request
    if (!out) throw std::runtime_error("write_calculix_deck: error while writing " + inp.string());
    return;
  }
  const double g = job.gravity.norm();
  if (g > 0.0) {
    const Eigen::Vector3d direction = job.gravity / g;
    out << "*DLOAD\nEALL, GRAV, " << exact(g) << ", " << exact(direction.x()) << ", " << exact(direction.y())
        << ", " << exact(direction.z()) << "\n";
  }
  any = false;
  for (Eigen::Index d = 0; d < job.nodal_loads.size(); ++d) {
    if (job.nodal_loads[d] == 0.0) continue;
    if (!any) out << "*CLOAD\n";
    any = true;
    out << d / 3 + 1 << ", " << d % 3 + 1 << ", " << exact(job.nodal_loads[d]) << "\n";
  }
  // ccx numbers the faces of C3D4/C3D10 as 1: (1,2,3), 2: (1,4,2), 3: (2,4,3), 4: (3,4,1);
  // Kerf names a face by its opposite corner: 3 -> 1, 2 -> 2, 0 -> 3, 1 -> 4.
  constexpr int ccx_face_of_opposite_corner[4] = {3, 4, 2, 1};
  if (!job.face_pressures.empty()) out << "*DLOAD\n";
  for (const FacePressure& load : job.face_pressures) {
    if (load.tet < 0 || load.tet >= mesh.num_tets() || load.local_face < 0 || load.local_face > 3)
      throw std::invalid_argument("write_calculix_deck: face pressure on a face that does not exist");
    out << load.tet + 1 << ", P" << ccx_face_of_opposite_corner[load.local_face] << ", " << exact(load.pressure) << "\n";
  }
  out << "*NODE PRINT, NSET=NALL\nU\n*END STEP\n";
  if (!out) throw std::runtime_error("write_calculix_deck: error while writing " + inp.string());
}

double run_calculix(const std::string& ccx, const std::filesystem::path& workdir, const std::string& jobname) {
  if (ccx.empty()) throw std::runtime_error("run_calculix: no ccx executable given (calculix-ccx is required)");
  const std::filesystem::path log = workdir / (jobname + ".ccx.log");
  // One thread, so the wall times compare a serial ccx with a serial Kerf.
  const std::string command = "cd " + shell_quote(workdir.string()) + " && OMP_NUM_THREADS=1 " + shell_quote(ccx) +
                              " -i " + shell_quote(jobname) + " > " + shell_quote(log.string()) + " 2>&1";
  const auto start = std::chrono::steady_clock::now();
  const int status = std::system(command.c_str());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // ccx reports input errors as "*ERROR ..." lines, sometimes with exit status 0 and sometimes
  // before it crashes, so the log is read either way and its first error goes into the message.
  std::string error_line;
  std::ifstream in(log);
  for (std::string line; error_line.empty() && std::getline(in, line);)
    if (line.find("*ERROR") != std::string::npos) {
      error_line = trim(line);
      // ccx wraps its messages: "*ERROR reading *BOUNDARY: node set NOPE" / "has not yet been defined."
      if (std::getline(in, line) && !trim(line).empty() && trim(line)[0] != '*') error_line += " " + trim(line);
    }
  const bool exited_ok = status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (!exited_ok || !error_line.empty()) {
    std::string message = "run_calculix: ccx failed on " + (workdir / jobname).string() + ".inp";
    if (!exited_ok)
      message += " (exit status " + std::to_string(status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")";
    if (!error_line.empty()) message += ": " + error_line;
    throw std::runtime_error(message + "; see " + log.string());
  }
  return seconds;
}

Eigen::MatrixXd read_calculix_displacements(const std::filesystem::path& dat, Eigen::Index num_nodes) {
  std::ifstream in(dat);
  if (!in) throw std::runtime_error("read_calculix_displacements: cannot open " + dat.string());
  Eigen::MatrixXd u;
  bool in_block = false;
  for (std::string line; std::getline(in, line);) {
    if (line.find("displacements (vx,vy,vz)") != std::string::npos) {
      u = Eigen::MatrixXd::Zero(num_nodes, 3); // a later step overwrites an earlier one
      in_block = true;
      continue;
    }
    if (!in_block) continue;
    std::istringstream fields(line);
    Eigen::Index node = 0;
    std::string x, y, z;
    if (!(fields >> node >> x >> y >> z)) {
      if (line.find_first_not_of(" \t\r") != std::string::npos) in_block = false; // next block's header
      continue;
    }
    if (node < 1 || node > num_nodes)
      throw std::runtime_error("read_calculix_displacements: node " + std::to_string(node) + " out of range in " +
                               dat.string());
    u.row(node - 1) << parse_fortran_double(x), parse_fortran_double(y), parse_fortran_double(z);
  }
  if (u.size() == 0) throw std::runtime_error("read_calculix_displacements: no displacement block in " + dat.string());
  return u;
}

std::vector<double> read_calculix_eigenvalues(const std::filesystem::path& dat) {
  std::ifstream in(dat);
  if (!in) throw std::runtime_error("read_calculix_eigenvalues: cannot open " + dat.string());
  std::vector<double> eigenvalues;
  bool in_block = false;
  for (std::string line; std::getline(in, line);) {
    if (line.find("E I G E N V A L U E   O U T P U T") != std::string::npos) {
      eigenvalues.clear(); // a later step overwrites an earlier one
      in_block = true;
      continue;
    }
    if (!in_block) continue;
    // Rows "mode eigenvalue omega frequency imaginary"; the header lines do not parse as such,
    // and the next block's title ends this one.
    if (line.find("P A R T I C I P A T I O N") != std::string::npos || line.find("E F F E C T I V E") != std::string::npos) break;
    std::istringstream fields(line);
    int mode = 0;
    std::string value;
    if (!(fields >> mode >> value)) continue;
    if (mode != static_cast<int>(eigenvalues.size()) + 1)
      throw std::runtime_error("read_calculix_eigenvalues: mode " + std::to_string(mode) + " out of order in " + dat.string());
    eigenvalues.push_back(parse_fortran_double(value));
  }
  if (eigenvalues.empty()) throw std::runtime_error("read_calculix_eigenvalues: no eigenvalue block in " + dat.string());
  return eigenvalues;
}

CalculixMatrices read_calculix_matrices(const std::filesystem::path& job_base, Eigen::Index num_nodes) {
  CalculixMatrices m;
  const std::filesystem::path dof_file = job_base.string() + ".dof";
  std::ifstream in(dof_file);
  if (!in) throw std::runtime_error("read_calculix_matrices: cannot open " + dof_file.string());
  // Each line is "node.direction": the node and the global direction (1..3) of that row.
  for (std::string entry; in >> entry;) {
    const auto dot = entry.find('.');
    if (dot == std::string::npos) throw std::runtime_error("read_calculix_matrices: bad entry " + entry);
    const Eigen::Index node = std::stol(entry.substr(0, dot));
    const int direction = std::stoi(entry.substr(dot + 1));
    if (node < 1 || node > num_nodes || direction < 1 || direction > 3)
      throw std::runtime_error("read_calculix_matrices: DOF " + entry + " out of range in " + dof_file.string());
    m.dof.push_back(3 * (node - 1) + direction - 1);
  }
  const auto n = static_cast<Eigen::Index>(m.dof.size());
  if (n == 0) throw std::runtime_error("read_calculix_matrices: empty " + dof_file.string());
  m.stiffness = read_triangle_file(job_base.string() + ".sti", n);
  m.mass = read_triangle_file(job_base.string() + ".mas", n);
  return m;
}

Eigen::MatrixXd solve_calculix_matrices(const CalculixMatrices& matrices, Eigen::Index num_nodes,
                                        const CalculixJob& job) {
  const DofMap dofs = make_dof_map(num_nodes, job.dirichlet);
  const auto n = static_cast<Eigen::Index>(matrices.dof.size());

  // The consistent body load is f_i = sum_j M_ij g_j: the shape functions sum to one, so
  // int rho N_i g dV = sum_j (int rho N_i N_j dV) g_j, with ccx's own quadrature on both sides.
  Eigen::VectorXd g_rows(n), u_prescribed(n), f_rows(n);
  for (Eigen::Index r = 0; r < n; ++r) {
    const Eigen::Index d = matrices.dof[static_cast<std::size_t>(r)];
    g_rows[r] = job.gravity[d % 3];
    u_prescribed[r] = dofs.prescribed[d];
    f_rows[r] = job.nodal_loads.size() != 0 ? job.nodal_loads[d] : 0.0;
  }
  f_rows += matrices.mass * g_rows;

  // Partition ccx's rows into unknown (a) and prescribed (b): K_aa u_a = f_a - K_ab u_b.
  std::vector<Eigen::Index> unknown_of_row(static_cast<std::size_t>(n), -1);
  Eigen::Index na = 0;
  for (Eigen::Index r = 0; r < n; ++r)
    if (dofs.free_index[static_cast<std::size_t>(matrices.dof[static_cast<std::size_t>(r)])] >= 0)
      unknown_of_row[static_cast<std::size_t>(r)] = na++;
  Eigen::VectorXd u_b = u_prescribed;
  for (Eigen::Index r = 0; r < n; ++r)
    if (unknown_of_row[static_cast<std::size_t>(r)] >= 0) u_b[r] = 0.0;
  const Eigen::VectorXd rhs_rows = f_rows - matrices.stiffness * u_b;

  std::vector<Eigen::Triplet<double>> triplets;
  for (Eigen::Index c = 0; c < matrices.stiffness.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(matrices.stiffness, c); it; ++it) {
      const Eigen::Index i = unknown_of_row[static_cast<std::size_t>(it.row())];
      const Eigen::Index j = unknown_of_row[static_cast<std::size_t>(it.col())];
      if (i >= 0 && j >= 0) triplets.emplace_back(i, j, it.value());
    }
  Eigen::SparseMatrix<double> k_aa(na, na);
  k_aa.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::VectorXd f_a(na);
  for (Eigen::Index r = 0; r < n; ++r)
    if (unknown_of_row[static_cast<std::size_t>(r)] >= 0) f_a[unknown_of_row[static_cast<std::size_t>(r)]] = rhs_rows[r];

  // Eigen's own LDL^T, not the solver Kerf uses, so the check shares no code with Kerf's solve.
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(k_aa);
  if (ldlt.info() != Eigen::Success)
    throw std::runtime_error("solve_calculix_matrices: CalculiX's K_ff is singular (too few Dirichlet nodes?)");
  const Eigen::VectorXd u_a = ldlt.solve(f_a);

  // DOFs of nodes in no element are not in ccx's matrices: they keep their prescribed value.
  Eigen::MatrixXd u(num_nodes, 3);
  for (Eigen::Index d = 0; d < 3 * num_nodes; ++d) u(d / 3, d % 3) = dofs.prescribed[d];
  for (Eigen::Index r = 0; r < n; ++r) {
    const Eigen::Index d = matrices.dof[static_cast<std::size_t>(r)];
    const Eigen::Index a = unknown_of_row[static_cast<std::size_t>(r)];
    if (a >= 0) u(d / 3, d % 3) = u_a[a];
  }
  return u;
}

CalculixSolution solve_with_calculix(const std::string& ccx, const std::filesystem::path& workdir,
                                     const std::string& jobname, const TetMesh& mesh, CalculixJob job) {
  std::filesystem::create_directories(workdir);
  CalculixSolution s;

  job.procedure = CalculixProcedure::static_solve;
  const std::string static_job = jobname + "_static";
  write_calculix_deck(workdir / (static_job + ".inp"), mesh, job);
  s.static_seconds = run_calculix(ccx, workdir, static_job);
  s.static_displacement = read_calculix_displacements(workdir / (static_job + ".dat"), mesh.num_nodes());

  job.procedure = CalculixProcedure::matrix_storage;
  const std::string matrix_job = jobname + "_matrices";
  write_calculix_deck(workdir / (matrix_job + ".inp"), mesh, job);
  s.matrix_seconds = run_calculix(ccx, workdir, matrix_job);
  s.displacement = solve_calculix_matrices(read_calculix_matrices(workdir / matrix_job, mesh.num_nodes()),
                                           mesh.num_nodes(), job);
  return s;
}

} // namespace kerf
