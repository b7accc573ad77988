/// @file calculix_deck.hpp
/// @brief Solve Kerf's linear static problem with CalculiX (ccx) as an independent check.
///
/// Two routes, because ccx's usual output cannot show agreement to 1e-8:
///  - the static route (*STATIC) lets ccx assemble and solve, but the .dat prints U with only
///    7 significant digits (Fortran e13.6) and the .frd stores 4-byte floats;
///  - the matrix route (*FREQUENCY, SOLVER=MATRIXSTORAGE) makes ccx write its assembled
///    stiffness K and consistent mass M with 14 significant digits (%20.13e), plus the node
///    and direction of every row (.dof), and stop. Gravity's consistent load is exactly
///    f = M g (the shape functions sum to one, and M and the body force share ccx's
///    quadrature), so K u = M g + f_nodal, solved in double precision with the Dirichlet DOFs
///    eliminated, is CalculiX's discrete solution to solver precision.
/// The static route still exercises ccx's own loads and solver; the matrix route gives digits.
/// Their limit: rounding K to 14 digits moves u by about cond(K_ff) * 2e-16 relative (2e-10 for
/// a C3D10 bar of 4x2x2 cells, cond 1.2e6), so 1e-8 comparisons need cond(K_ff) below ~1e7.
#pragma once

#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <filesystem>
#include <string>
#include <vector>

namespace kerf {

/// What the deck asks ccx to do.
enum class CalculixProcedure {
  static_solve,   ///< *STATIC with *DLOAD GRAV and *CLOAD; U printed to jobname.dat (7 digits)
  matrix_storage, ///< *FREQUENCY, SOLVER=MATRIXSTORAGE: K, M and the DOF list to .sti/.mas/.dof
  frequency,      ///< *FREQUENCY with *BOUNDARY: the lowest `frequencies` eigenvalues to jobname.dat (ARPACK, 7 digits)
};

/// A uniform pressure on one face of one tet: ccx's *DLOAD "Pn", which ccx integrates itself.
/// Positive pressure pushes into the body: the force on the face is -pressure times its
/// outward normal times its area.
struct FacePressure {
  Eigen::Index tet = 0;  ///< Kerf tet index
  int local_face = 0;    ///< Kerf's face numbering: the index of the corner opposite the face
  double pressure = 0.0; ///< Pa
};

/// The linear static problem handed to CalculiX: material, Dirichlet nodes, gravity, nodal loads.
struct CalculixJob {
  LinearMaterial material;                ///< E, nu and rho (rho > 0 for the matrix route)
  std::vector<DirichletNodes> dirichlet;  ///< prescribed nodes, resolved as make_dof_map does
  Eigen::Vector3d gravity{0.0, 0.0, 0.0}; ///< body acceleration g in m/s^2 (force density rho g)
  Eigen::VectorXd nodal_loads;            ///< empty, or 3#V node-major concentrated forces in N
  /// Face pressures, static route only: the matrix route has no load vector but M g and the
  /// nodal loads, so a traction must be given there as nodal_loads.
  std::vector<FacePressure> face_pressures;
  CalculixProcedure procedure = CalculixProcedure::static_solve; ///< which deck to write
  int frequencies = 10; ///< frequency route: how many of the lowest eigenvalues ccx computes (needs rho > 0, no loads)

  /// Static route only: a geometrically nonlinear step (*STEP, NLGEOM). ccx then reads
  /// *ELASTIC as a St. Venant-Kirchhoff material (Green-Lagrange strain, second Piola-Kirchhoff
  /// stress) and ramps the loads over the step time 1 in automatic increments; loads are dead
  /// (fixed direction). The .dat then holds one U block per increment, the last one the answer.
  bool nlgeom = false;
  double initial_increment = 0.1; ///< NLGEOM: first increment, a fraction of the step time 1
  double min_increment = 1e-5;    ///< NLGEOM: ccx gives up below this increment
  double max_increment = 0.1;     ///< NLGEOM: largest increment
  int max_increments = 1000;      ///< NLGEOM: the step's INC= limit
};

/// Writes a CalculiX input deck (C3D4 or C3D10) for `mesh` and `job`.
///
/// Kerf node v is ccx node v + 1 and tet t is element t + 1; Kerf's Tet10 node order is already
/// ccx's C3D10 order. Numbers are written with 17 significant digits so the deck round-trips
/// doubles exactly. The matrix deck has no *BOUNDARY: a constrained model's .sti and .mas lack
/// the columns of the constrained DOFs, which M g and the lifting K_fc u_c both need, so ccx
/// stores the whole K and M and solve_calculix_matrices eliminates the Dirichlet DOFs.
/// @param inp  path of the .inp file to write
/// @param mesh Tet4 or Tet10 mesh
/// @param job  material, boundary conditions, loads and procedure
/// @throws std::invalid_argument on inconsistent sizes, std::runtime_error if the file fails
void write_calculix_deck(const std::filesystem::path& inp, const TetMesh& mesh, const CalculixJob& job);

/// Runs `ccx -i jobname` in `workdir`, its output going to workdir/jobname.ccx.log.
/// @param ccx     path of the ccx executable
/// @param workdir folder holding jobname.inp; ccx writes its files there
/// @param jobname the deck's name without ".inp"
/// @return wall time of the ccx process in seconds (process start-up included)
/// @throws std::runtime_error with a one-line message if ccx cannot run, fails or reports *ERROR
double run_calculix(const std::string& ccx, const std::filesystem::path& workdir, const std::string& jobname);

/// Reads the last "displacements (vx,vy,vz)" block of a ccx .dat file (*NODE PRINT, U).
/// @param dat       the jobname.dat file
/// @param num_nodes #V; ccx node n is row n - 1
/// @return #V by 3 displacements (7 significant digits); nodes ccx did not print stay 0
/// @throws std::runtime_error if the file or the block is missing or a node is out of range
Eigen::MatrixXd read_calculix_displacements(const std::filesystem::path& dat, Eigen::Index num_nodes);

/// Reads the "E I G E N V A L U E   O U T P U T" block of a ccx .dat file (*FREQUENCY): the
/// eigenvalues omega^2 (1/s^2 in SI units), mode 1 first, with ccx's 7 significant digits.
/// @throws std::runtime_error if the file or the block is missing
std::vector<double> read_calculix_eigenvalues(const std::filesystem::path& dat);

/// CalculiX's assembled matrices over the DOFs of its equations (all of them when the deck has
/// no *BOUNDARY), as written by the matrix-storage route.
struct CalculixMatrices {
  Eigen::SparseMatrix<double> stiffness; ///< K, both triangles filled, n by n
  Eigen::SparseMatrix<double> mass;      ///< consistent M, both triangles filled, n by n
  std::vector<Eigen::Index> dof;         ///< Kerf DOF 3 v + p of each of the n rows
};

/// Reads jobname.sti, jobname.mas and jobname.dof written by *FREQUENCY, SOLVER=MATRIXSTORAGE.
/// @param job_base  workdir / jobname, without extension
/// @param num_nodes #V, to check the DOF list
/// @return the matrices and the row-to-DOF map
/// @throws std::runtime_error if a file is missing or malformed
CalculixMatrices read_calculix_matrices(const std::filesystem::path& job_base, Eigen::Index num_nodes);

/// Solves K u = M g + f_nodal in double precision with CalculiX's K and M.
///
/// The DOFs prescribed in `job` are eliminated, K_ff u_f = f_f - K_fc u_c, and the rest is
/// solved with Eigen's SimplicialLDLT; DOFs absent from ccx's matrices (nodes in no element)
/// take their prescribed value, or 0.
/// @param matrices  from read_calculix_matrices
/// @param num_nodes #V
/// @param job       the job the matrices were written for
/// @return #V by 3 displacements, CalculiX's discrete solution to solver precision
Eigen::MatrixXd solve_calculix_matrices(const CalculixMatrices& matrices, Eigen::Index num_nodes,
                                        const CalculixJob& job);

/// Everything one validation run gives back.
struct CalculixSolution {
  Eigen::MatrixXd displacement;        ///< #V by 3, matrix route, full precision
  Eigen::MatrixXd static_displacement; ///< #V by 3, ccx's own static solve, 7 significant digits
  double static_seconds = 0.0;         ///< wall time of the static ccx run
  double matrix_seconds = 0.0;         ///< wall time of the matrix-storage ccx run
};

/// Runs both routes in `workdir` (created if needed) as jobs "<jobname>_static" and
/// "<jobname>_matrices", and returns ccx's displacements and wall times.
/// @param ccx     path of the ccx executable
/// @param workdir folder for the decks and ccx's output
/// @param jobname stem of the two job names
/// @param mesh    Tet4 or Tet10 mesh
/// @param job     material, boundary conditions and loads (its procedure field is ignored)
/// @return both displacements and both wall times
CalculixSolution solve_with_calculix(const std::string& ccx, const std::filesystem::path& workdir,
                                     const std::string& jobname, const TetMesh& mesh, CalculixJob job);

} // namespace kerf
