#include "kerf/mesh/point_locator.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace kerf {

PointLocator::PointLocator(const TetMesh& mesh) : mesh_(mesh) {
  lower_ = mesh.nodes.colwise().minCoeff().transpose();
  const Eigen::Vector3d upper = mesh.nodes.colwise().maxCoeff().transpose();
  Eigen::Vector3d extent = (upper - lower_).cwiseMax(1e-12 * (upper - lower_).norm());
  // Buckets of about equal sides, with about as many buckets as tets.
  const double side = std::cbrt(extent.prod() / std::max<double>(1.0, static_cast<double>(mesh.num_tets())));
  for (int i = 0; i < 3; ++i) buckets_[i] = std::clamp(static_cast<int>(std::ceil(extent[i] / side)), 1, 1000);
  bucket_size_ = extent.cwiseQuotient(buckets_.cast<double>());

  const auto num_buckets = static_cast<std::size_t>(buckets_.prod());
  std::vector<std::vector<int>> lists(num_buckets);
  boxes_.resize(static_cast<std::size_t>(mesh.num_tets()));
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    Eigen::Vector3d lo = mesh.nodes.row(mesh.tets(t, 0)).transpose(), hi = lo;
    for (int a = 1; a < 4; ++a) {
      lo = lo.cwiseMin(mesh.nodes.row(mesh.tets(t, a)).transpose());
      hi = hi.cwiseMax(mesh.nodes.row(mesh.tets(t, a)).transpose());
    }
    // x = sum lambda_a x_a with sum lambda_a = 1 and every lambda_a >= -1e-10 lies within
    // 4e-10 of the corners' extent of the box: 1e-9 of the diagonal is a safe margin.
    const Eigen::Vector3d margin = Eigen::Vector3d::Constant(1e-9 * (hi - lo).norm());
    boxes_[static_cast<std::size_t>(t)] = Eigen::AlignedBox3d(lo - margin, hi + margin);
    const Eigen::Vector3i b0 = bucket_of(lo), b1 = bucket_of(hi);
    for (int k = b0[2]; k <= b1[2]; ++k)
      for (int j = b0[1]; j <= b1[1]; ++j)
        for (int i = b0[0]; i <= b1[0]; ++i)
          lists[static_cast<std::size_t>(i + buckets_[0] * (j + buckets_[1] * k))].push_back(static_cast<int>(t));
  }
  bucket_start_.assign(num_buckets + 1, 0);
  for (std::size_t b = 0; b < num_buckets; ++b) bucket_start_[b + 1] = bucket_start_[b] + static_cast<int>(lists[b].size());
  bucket_tets_.reserve(static_cast<std::size_t>(bucket_start_.back()));
  for (const auto& list : lists) bucket_tets_.insert(bucket_tets_.end(), list.begin(), list.end());
}

Eigen::Vector3i PointLocator::bucket_of(const Eigen::Vector3d& x) const {
  Eigen::Vector3i b;
  for (int i = 0; i < 3; ++i)
    b[i] = std::clamp(static_cast<int>(std::floor((x[i] - lower_[i]) / bucket_size_[i])), 0, buckets_[i] - 1);
  return b;
}

PointLocation PointLocator::locate(const Eigen::Vector3d& x) const {
  PointLocation best;
  if (!x.allFinite()) return best;
  // A point beyond the grid (by more than a bucket) cannot be inside any tet.
  const Eigen::Vector3d upper = lower_ + bucket_size_.cwiseProduct(buckets_.cast<double>());
  if (((x - lower_).array() < -bucket_size_.array()).any() || ((x - upper).array() > bucket_size_.array()).any()) return best;
  const Eigen::Vector3i b = bucket_of(x);
  const auto bucket = static_cast<std::size_t>(b[0] + buckets_[0] * (b[1] + buckets_[1] * b[2]));
  double best_min_lambda = -1e-10;
  for (int i = bucket_start_[bucket]; i < bucket_start_[bucket + 1]; ++i) {
    const int t = bucket_tets_[static_cast<std::size_t>(i)];
    if (!boxes_[static_cast<std::size_t>(t)].contains(x)) continue;
    const Eigen::Vector3d x0 = mesh_.nodes.row(mesh_.tets(t, 0)).transpose();
    Eigen::Matrix3d J;
    for (int c = 0; c < 3; ++c) J.col(c) = mesh_.nodes.row(mesh_.tets(t, c + 1)).transpose() - x0;
    const Eigen::Vector3d xi = J.partialPivLu().solve(x - x0);
    const double min_lambda = std::min(1.0 - xi.sum(), xi.minCoeff());
    if (min_lambda >= best_min_lambda) {
      best_min_lambda = min_lambda;
      best.tet = t;
      best.xi = xi;
    }
  }
  return best;
}

} // namespace kerf
