// CorotatedPieces::step_terms four pieces at a time, the whole tets (four slots) and the special
// pieces of cut tets (eight, those a piece lacks with a zero gradient): the pass chapter 8's step
// makes five or more times a step, written so that each operation acts on four
// pieces with one vector instruction (AVX2 and FMA where the processor has them, chosen when the
// program starts; two SSE2 instructions elsewhere). The arithmetic is the scalar pass's
// (corotated_pieces.cpp), lane by lane: F (8.1), the warm rotation's Newton iterations with the
// Cayley turn, the strain and stress (8.2), (8.3), the damping term's warped strain, and the force
// V (R sigma + c Q sigma_d) g_s. Gathering u and scattering the forces stay scalar (the lanes'
// nodes differ). A lane whose F is inverted, whose Newton matrix is not positive definite or whose
// rotation does not converge in 8 iterations is done again the scalar way, which falls back to
// chapter 2's decomposition. warped_product (K_R d) and gradient_sums (the step's reference
// gradients) have their own, shorter passes over the same blocks.
//
// No Eigen type crosses into the vectorised function: it is compiled twice (for AVX2 and FMA, and
// for SSE2), and only plain arrays and GCC's vector extensions live in it.
#include "kerf/corotation/corotated_pieces.hpp"

#include <cstring>

namespace kerf {

namespace {

typedef double Lanes __attribute__((vector_size(32)));          // one value of each of four pieces
typedef long long LaneMask __attribute__((vector_size(32)));     // a comparison's result: -1 or 0

// A 3x3 matrix of four pieces, column-major like Eigen's: m[i + 3 j] is entry (i, j).
struct Lanes3x3 {
  Lanes m[9];
};

// What the vectorised pass gives back for the block's four lanes.
struct LaneResults {
  double W[4], half_dKd[4];
  int scalar[4]; // 1: not done here (no force added, rotation not stored)
};

// The block's data, as plain arrays (PieceBlockOf's layout), `slots` slots a lane.
template <int slots>
struct BlockView {
  const int (*dof)[4];             // [slot][lane]
  const double (*gradient)[3][4];  // [slot][component][lane]
  const double* volume;            // [lane]
  const std::size_t* piece;        // [lane]
};

// The block's gradients g_s, lane by lane, and sum_s q_s g_s^T with q gathered lane by lane.
template <int slots>
__attribute__((always_inline)) inline void load_gradients(const BlockView<slots>& block, Lanes (&g)[slots][3]) {
  for (int s = 0; s < slots; ++s)
    for (int i = 0; i < 3; ++i) std::memcpy(&g[s][i], block.gradient[s][i], sizeof(Lanes));
}
template <int slots>
__attribute__((always_inline)) inline void gradient_sum(const BlockView<slots>& block, const Lanes (&g)[slots][3], const double* q,
                                                        Lanes3x3& sum) {
  for (Lanes& v : sum.m) v = Lanes{0, 0, 0, 0};
  for (int s = 0; s < slots; ++s) {
    const int* dof = block.dof[s];
    for (int i = 0; i < 3; ++i) {
      const Lanes q_i = {q[dof[0] + i], q[dof[1] + i], q[dof[2] + i], q[dof[3] + i]};
      for (int j = 0; j < 3; ++j) sum.m[i + 3 * j] += q_i * g[s][j];
    }
  }
}

// The pass over one block. Inlined into two functions below, one compiled for AVX2 and FMA.
template <int slots>
__attribute__((always_inline)) inline void block_pass(const BlockView<slots>& block, const double* u, const double* reference_sums,
                                                      const double* turned, double* rotations, double* force, double c, double mu,
                                                      double lambda, double tolerance, LaneResults& out) {
  const Lanes zero = {0, 0, 0, 0}, one = {1, 1, 1, 1};
  Lanes g[slots][3]; // [slot][component]
  load_gradients(block, g);
  Lanes3x3 grad_u; // sum_s u_s g_s^T (8.1)
  gradient_sum(block, g, u, grad_u);
  Lanes3x3 F = grad_u;
  F.m[0] += one, F.m[4] += one, F.m[8] += one;
  const Lanes det_F = F.m[0] * (F.m[4] * F.m[8] - F.m[5] * F.m[7]) - F.m[3] * (F.m[1] * F.m[8] - F.m[2] * F.m[7]) +
                      F.m[6] * (F.m[1] * F.m[5] - F.m[2] * F.m[4]);
  // The lanes' rotations, from the last evaluation's (rotations: one column-major 3x3 a piece).
  Lanes3x3 R;
  for (int k = 0; k < 9; ++k)
    R.m[k] = Lanes{rotations[9 * block.piece[0] + k], rotations[9 * block.piece[1] + k], rotations[9 * block.piece[2] + k],
                   rotations[9 * block.piece[3] + k]};
  // The warm rotation (corotated_pieces.cpp's warm_rotation): Newton on skew(R^T F) = 0, a lane
  // stopping once its correction is below the tolerance.
  LaneMask scalar = det_F <= zero;
  LaneMask active = ~scalar;
  Lanes3x3 A;
  for (int iteration = 0; iteration < 8; ++iteration) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) A.m[i + 3 * j] = R.m[3 * i] * F.m[3 * j] + R.m[1 + 3 * i] * F.m[1 + 3 * j] + R.m[2 + 3 * i] * F.m[2 + 3 * j];
    const Lanes skew_x = A.m[5] - A.m[7], skew_y = A.m[6] - A.m[2], skew_z = A.m[1] - A.m[3];
    const Lanes trace = A.m[0] + A.m[4] + A.m[8];
    const Lanes h00 = trace - A.m[0], h11 = trace - A.m[4], h22 = trace - A.m[8];
    const Lanes h01 = -0.5 * (A.m[3] + A.m[1]), h02 = -0.5 * (A.m[6] + A.m[2]), h12 = -0.5 * (A.m[7] + A.m[5]);
    const Lanes a00 = h11 * h22 - h12 * h12, a11 = h00 * h22 - h02 * h02, a22 = h00 * h11 - h01 * h01;
    const Lanes a01 = h02 * h12 - h01 * h22, a02 = h01 * h12 - h02 * h11, a12 = h01 * h02 - h00 * h12;
    const Lanes det_H = h00 * a00 + h01 * a01 + h02 * a02;
    scalar |= active & ~((det_H > zero) & (h00 > zero));
    active &= ~scalar;
    const Lanes half = 0.5 / (det_H + (det_H == zero ? one : zero));
    const Lanes wx = half * (a00 * skew_x + a01 * skew_y + a02 * skew_z);
    const Lanes wy = half * (a01 * skew_x + a11 * skew_y + a12 * skew_z);
    const Lanes wz = half * (a02 * skew_x + a12 * skew_y + a22 * skew_z);
    const Lanes w2 = wx * wx + wy * wy + wz * wz;
    const Lanes k = 2.0 / (one + w2);
    // The turn I + k ([w] + [w]^2), [w]^2 = w w^T - |w|^2 I.
    Lanes3x3 T;
    T.m[0] = one + k * (wx * wx - w2), T.m[4] = one + k * (wy * wy - w2), T.m[8] = one + k * (wz * wz - w2);
    T.m[3] = k * (wx * wy - wz), T.m[1] = k * (wx * wy + wz); // (0, 1), (1, 0)
    T.m[6] = k * (wx * wz + wy), T.m[2] = k * (wx * wz - wy); // (0, 2), (2, 0)
    T.m[7] = k * (wy * wz - wx), T.m[5] = k * (wy * wz + wx); // (1, 2), (2, 1)
    Lanes3x3 turned_R;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        turned_R.m[i + 3 * j] = R.m[i] * T.m[3 * j] + R.m[i + 3] * T.m[1 + 3 * j] + R.m[i + 6] * T.m[2 + 3 * j];
    for (int m = 0; m < 9; ++m) R.m[m] = active ? turned_R.m[m] : R.m[m];
    active &= ~(4.0 * w2 < tolerance * tolerance);
    bool any = false;
    for (int lane = 0; lane < 4; ++lane) any = any || active[lane];
    if (!any) break;
  }
  scalar |= active; // not converged in 8 iterations
  // The strain sym(R^T F) - I (8.2), the damping term's sym(Q^T (grad u - sum of u_ref)).
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) A.m[i + 3 * j] = R.m[3 * i] * F.m[3 * j] + R.m[1 + 3 * i] * F.m[1 + 3 * j] + R.m[2 + 3 * i] * F.m[2 + 3 * j];
  Lanes3x3 Q, D;
  for (int k = 0; k < 9; ++k) {
    Q.m[k] = Lanes{turned[9 * block.piece[0] + k], turned[9 * block.piece[1] + k], turned[9 * block.piece[2] + k], turned[9 * block.piece[3] + k]};
    D.m[k] = grad_u.m[k] - Lanes{reference_sums[9 * block.piece[0] + k], reference_sums[9 * block.piece[1] + k],
                                 reference_sums[9 * block.piece[2] + k], reference_sums[9 * block.piece[3] + k]};
  }
  Lanes3x3 B; // Q^T D
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) B.m[i + 3 * j] = Q.m[3 * i] * D.m[3 * j] + Q.m[1 + 3 * i] * D.m[1 + 3 * j] + Q.m[2 + 3 * i] * D.m[2 + 3 * j];
  Lanes3x3 strain, rate;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      strain.m[i + 3 * j] = 0.5 * (A.m[i + 3 * j] + A.m[j + 3 * i]);
      rate.m[i + 3 * j] = 0.5 * (B.m[i + 3 * j] + B.m[j + 3 * i]);
    }
  strain.m[0] -= one, strain.m[4] -= one, strain.m[8] -= one;
  const Lanes tr_strain = strain.m[0] + strain.m[4] + strain.m[8], tr_rate = rate.m[0] + rate.m[4] + rate.m[8];
  Lanes squared_strain = zero, squared_rate = zero;
  for (int m = 0; m < 9; ++m) squared_strain += strain.m[m] * strain.m[m], squared_rate += rate.m[m] * rate.m[m];
  Lanes volume;
  std::memcpy(&volume, block.volume, sizeof(Lanes));
  const Lanes W = volume * (mu * squared_strain + 0.5 * lambda * tr_strain * tr_strain);
  const Lanes half_dKd = volume * (mu * squared_rate + 0.5 * lambda * tr_rate * tr_rate);
  // sigma = 2 mu strain + lambda tr(strain) I, and V (R sigma + c Q sigma_d) (8.3).
  for (int m = 0; m < 9; ++m) strain.m[m] *= 2.0 * mu, rate.m[m] *= 2.0 * mu;
  for (int d = 0; d < 9; d += 4) strain.m[d] += lambda * tr_strain, rate.m[d] += lambda * tr_rate;
  Lanes3x3 P;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      P.m[i + 3 * j] = volume * (R.m[i] * strain.m[3 * j] + R.m[i + 3] * strain.m[1 + 3 * j] + R.m[i + 6] * strain.m[2 + 3 * j] +
                                 c * (Q.m[i] * rate.m[3 * j] + Q.m[i + 3] * rate.m[1 + 3 * j] + Q.m[i + 6] * rate.m[2 + 3 * j]));
  // The forces P g_s, scattered lane by lane; the rotations stored.
  for (int s = 0; s < slots; ++s)
    for (int i = 0; i < 3; ++i) {
      const Lanes f = P.m[i] * g[s][0] + P.m[i + 3] * g[s][1] + P.m[i + 6] * g[s][2];
      for (int lane = 0; lane < 4; ++lane)
        if (!scalar[lane]) force[block.dof[s][lane] + i] += f[lane];
    }
  for (int lane = 0; lane < 4; ++lane) {
    out.scalar[lane] = scalar[lane] ? 1 : 0;
    out.W[lane] = W[lane];
    out.half_dKd[lane] = half_dKd[lane];
    if (!scalar[lane])
      for (int k = 0; k < 9; ++k) rotations[9 * block.piece[lane] + k] = R.m[k][lane];
  }
}

template <int slots>
using BlockPass = void (*)(const BlockView<slots>&, const double*, const double*, const double*, double*, double*, double, double, double,
                           double, LaneResults&);

template <int slots>
__attribute__((target("avx2,fma"))) void block_pass_avx2(const BlockView<slots>& block, const double* u, const double* reference_sums,
                                                         const double* turned, double* rotations, double* force, double c, double mu,
                                                         double lambda, double tolerance, LaneResults& out) {
  block_pass(block, u, reference_sums, turned, rotations, force, c, mu, lambda, tolerance, out);
}

template <int slots>
void block_pass_sse2(const BlockView<slots>& block, const double* u, const double* reference_sums, const double* turned, double* rotations,
                     double* force, double c, double mu, double lambda, double tolerance, LaneResults& out) {
  block_pass(block, u, reference_sums, turned, rotations, force, c, mu, lambda, tolerance, out);
}

// AVX2 and FMA where this processor has both (asked once, when first needed), else SSE2, which
// every x86-64 has: of a pass compiled both ways, the one to call.
template <class Pass>
Pass chosen(Pass avx2, Pass sse2) {
  static const bool fast = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return fast ? avx2 : sse2;
}

// K_R d at the rotations `turned`, four pieces at a time (CorotatedPieces::warped_product):
// D = sum_s d_s g_s^T, the strain sym(Q^T D), sigma, the force V Q sigma g_s; its energy
// V psi into half_dKd, lane by lane.
template <int slots>
__attribute__((always_inline)) inline void warped_block_pass(const BlockView<slots>& block, const double* d, const double* turned,
                                                             double* K_d, double mu, double lambda, double* half_dKd) {
  const Lanes zero = {0, 0, 0, 0};
  Lanes g[slots][3];
  load_gradients(block, g);
  Lanes3x3 D, Q, B;
  gradient_sum(block, g, d, D);
  for (int k = 0; k < 9; ++k)
    Q.m[k] = Lanes{turned[9 * block.piece[0] + k], turned[9 * block.piece[1] + k], turned[9 * block.piece[2] + k], turned[9 * block.piece[3] + k]};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) B.m[i + 3 * j] = Q.m[3 * i] * D.m[3 * j] + Q.m[1 + 3 * i] * D.m[1 + 3 * j] + Q.m[2 + 3 * i] * D.m[2 + 3 * j];
  Lanes3x3 strain;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) strain.m[i + 3 * j] = 0.5 * (B.m[i + 3 * j] + B.m[j + 3 * i]);
  const Lanes trace = strain.m[0] + strain.m[4] + strain.m[8];
  Lanes squared = zero;
  for (int m = 0; m < 9; ++m) squared += strain.m[m] * strain.m[m];
  Lanes volume;
  std::memcpy(&volume, block.volume, sizeof(Lanes));
  const Lanes energy = volume * (mu * squared + 0.5 * lambda * trace * trace);
  for (int m = 0; m < 9; ++m) strain.m[m] *= 2.0 * mu;
  for (int m = 0; m < 9; m += 4) strain.m[m] += lambda * trace;
  Lanes3x3 P;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      P.m[i + 3 * j] = volume * (Q.m[i] * strain.m[3 * j] + Q.m[i + 3] * strain.m[1 + 3 * j] + Q.m[i + 6] * strain.m[2 + 3 * j]);
  for (int s = 0; s < slots; ++s)
    for (int i = 0; i < 3; ++i) {
      const Lanes f = P.m[i] * g[s][0] + P.m[i + 3] * g[s][1] + P.m[i + 6] * g[s][2];
      for (int lane = 0; lane < 4; ++lane) K_d[block.dof[s][lane] + i] += f[lane];
    }
  for (int lane = 0; lane < 4; ++lane) half_dKd[lane] = energy[lane];
}

template <int slots>
using WarpedPass = void (*)(const BlockView<slots>&, const double*, const double*, double*, double, double, double*);

template <int slots>
__attribute__((target("avx2,fma"))) void warped_block_pass_avx2(const BlockView<slots>& block, const double* d, const double* turned,
                                                                double* K_d, double mu, double lambda, double* half_dKd) {
  warped_block_pass(block, d, turned, K_d, mu, lambda, half_dKd);
}

template <int slots>
void warped_block_pass_sse2(const BlockView<slots>& block, const double* d, const double* turned, double* K_d, double mu, double lambda,
                            double* half_dKd) {
  warped_block_pass(block, d, turned, K_d, mu, lambda, half_dKd);
}

// sum_s q_s g_s^T of a block's four pieces (CorotatedPieces::gradient_sums), stored piece by
// piece; a lane without a piece repeats lane 0's piece and slots, and so its sum.
template <int slots>
__attribute__((always_inline)) inline void sums_block_pass(const BlockView<slots>& block, const double* q, double* sums) {
  Lanes g[slots][3];
  load_gradients(block, g);
  Lanes3x3 sum;
  gradient_sum(block, g, q, sum);
  for (int lane = 0; lane < 4; ++lane)
    for (int k = 0; k < 9; ++k) sums[9 * block.piece[lane] + k] = sum.m[k][lane];
}

template <int slots>
using SumsPass = void (*)(const BlockView<slots>&, const double*, double*);

template <int slots>
__attribute__((target("avx2,fma"))) void sums_block_pass_avx2(const BlockView<slots>& block, const double* q, double* sums) {
  sums_block_pass(block, q, sums);
}

template <int slots>
void sums_block_pass_sse2(const BlockView<slots>& block, const double* q, double* sums) {
  sums_block_pass(block, q, sums);
}

} // namespace

// The blocks' pass, and the lanes it leaves to the scalar way (piece_step_terms).
template <int slots, class Block>
CorotatedPieces::StepTerms CorotatedPieces::step_terms_of_blocks(const std::vector<Block>& blocks, const double* volumes, const Eigen::VectorXd& u,
                                                              const std::vector<Eigen::Matrix3d>& reference_sums, double c,
                                                              const std::vector<Eigen::Matrix3d>& turned, Eigen::VectorXd& force,
                                                              std::vector<Eigen::Matrix3d>& rotations, double turn_tolerance) const {
  StepTerms terms;
  LaneResults lanes;
  const BlockPass<slots> pass = chosen<BlockPass<slots>>(block_pass_avx2<slots>, block_pass_sse2<slots>);
  for (const Block& block : blocks) {
    const BlockView<slots> view{block.dof, block.gradient, volumes, block.piece};
    volumes += 4;
    pass(view, u.data(), reference_sums.data()->data(), turned.data()->data(), rotations.data()->data(), force.data(), c, mu_, lambda_,
         turn_tolerance, lanes);
    for (int lane = 0; lane < 4; ++lane) {
      if (view.volume[lane] == 0.0) continue; // a special tet's whole piece, or a lane without a piece
      if (lanes.scalar[lane]) {
        const std::size_t p = block.piece[lane];
        const StepTerms piece = piece_step_terms(p, u, reference_sums[p], c, turned[p], force, rotations[p], turn_tolerance);
        terms.W += piece.W;
        terms.half_dKd += piece.half_dKd;
      } else {
        terms.W += lanes.W[lane];
        terms.half_dKd += lanes.half_dKd[lane];
      }
    }
  }
  return terms;
}

CorotatedPieces::StepTerms CorotatedPieces::block_step_terms(const Eigen::VectorXd& u, const std::vector<Eigen::Matrix3d>& reference_sums,
                                                             double c, const std::vector<Eigen::Matrix3d>& turned, Eigen::VectorXd& force,
                                                             std::vector<Eigen::Matrix3d>& rotations, double turn_tolerance) const {
  StepTerms terms = step_terms_of_blocks<4>(whole_->blocks, whole_volume_.data(), u, reference_sums, c, turned, force, rotations, turn_tolerance);
  const StepTerms special = step_terms_of_blocks<8>(special_blocks_, special_block_volume_.data(), u, reference_sums, c, turned, force, rotations,
                                                 turn_tolerance);
  terms.W += special.W;
  terms.half_dKd += special.half_dKd;
  return terms;
}

// K_R d and 1/2 d^T K_R d of one kind of block.
template <int slots, class Block>
double CorotatedPieces::warped_product_of_blocks(const std::vector<Block>& blocks, const double* volumes,
                                              const std::vector<Eigen::Matrix3d>& rotations, const Eigen::VectorXd& d,
                                              Eigen::VectorXd& K_d) const {
  const WarpedPass<slots> pass = chosen<WarpedPass<slots>>(warped_block_pass_avx2<slots>, warped_block_pass_sse2<slots>);
  double half_dKd = 0.0, lanes[4];
  for (const Block& block : blocks) {
    const BlockView<slots> view{block.dof, block.gradient, volumes, block.piece};
    volumes += 4;
    pass(view, d.data(), rotations.data()->data(), K_d.data(), mu_, lambda_, lanes);
    half_dKd += (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
  }
  return half_dKd;
}

double CorotatedPieces::block_warped_product(const std::vector<Eigen::Matrix3d>& rotations, const Eigen::VectorXd& d,
                                             Eigen::VectorXd& K_d) const {
  return warped_product_of_blocks<4>(whole_->blocks, whole_volume_.data(), rotations, d, K_d) +
         warped_product_of_blocks<8>(special_blocks_, special_block_volume_.data(), rotations, d, K_d);
}

// The gradient sums of one kind of block.
template <int slots, class Block>
void CorotatedPieces::gradient_sums_of_blocks(const std::vector<Block>& blocks, const Eigen::VectorXd& q,
                                              std::vector<Eigen::Matrix3d>& sums) const {
  const SumsPass<slots> pass = chosen<SumsPass<slots>>(sums_block_pass_avx2<slots>, sums_block_pass_sse2<slots>);
  for (const Block& block : blocks) pass({block.dof, block.gradient, nullptr, block.piece}, q.data(), sums.data()->data());
}

void CorotatedPieces::block_gradient_sums(const Eigen::VectorXd& q, std::vector<Eigen::Matrix3d>& sums) const {
  gradient_sums_of_blocks<4>(whole_->blocks, q, sums);
  gradient_sums_of_blocks<8>(special_blocks_, q, sums);
}

} // namespace kerf
