#pragma once
/// \file returns_stage.h Stage 7, for LiDAR views: point-to-plane rounds on the sweeps' own
/// returns from the claimed pose.
///
/// A LiDAR view is segmented on binned cells (range_view.h). A binned cell is the mean of
/// different returns in each view (the bins fall elsewhere on the scene when the sensor turns),
/// so terms between cells leave a bias of a few tenths of a degree; a return has its own place on
/// the other sweep's surface. When both views carry their returns (DepthView::returns) and a full
/// pose is claimed, registerViews() and trackViews() end with these rounds; their pose and
/// information replace the cells' (PairResult::returns_refined), or, when they fail, the cells'
/// pose stays and PairResult::returns_reason says why. Without a prior (registerViews,
/// registerViewSets), their pose is also restarted along its weakest translation (returnsBasin):
/// a likelier minimum found so replaces it when better by the uniqueness test's margin, and
/// otherwise refuses it.
#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/core/range_scan.h"
#include "gasp/pipeline/visibility_check.h"
#include "gasp/registration/refinement.h"

namespace gasp {

struct ReturnsRefineParams {
  /// Round r's gate on the point-to-plane distance [m], the last for the rounds after the third.
  /// (A fixed array: a std::vector here, in every PairParams, sets off GCC 12's false
  /// -Wmaybe-uninitialized in the callers that copy one.)
  std::array<double, 3> gates_m = {0.3, 0.15, 0.08};
  int column_step = 1;          ///< every n-th column of the source sweep
  int return_step = 1;          ///< then every n-th of those columns' valid returns (a claimed pose's basin restarts with 2)
  int look_up_columns = 2;      ///< a point takes the nearest return with a normal within this many columns
  int max_rounds = 10;          ///< rounds in all (the last gate repeats until converged)
  double converged_m = 0.0005;  ///< RMS displacement of the source returns that ends the rounds [m]
  /// A return's normal: a plane fitted to the 3 x (2 half_width + 1) returns around it (grown
  /// against the range noise: normal_noise_m), kept when its thinnest spread is below
  /// max_flatness of the next (a surface, not an edge or foliage).
  /// 0: the columns that span the rows' pitch either side, so the window is square in view angle
  /// and the plane's tilt is determined as well along the rows as across them
  /// (squareNormalHalfWidth(): 10 for a VLP-16's 2 deg rows and 0.2 deg columns, 2 for 64 lasers).
  int normal_half_width = 0;
  double max_flatness = 0.3;
  /// The range noise (1 sigma) [m] the window grows against. On a plane measured with noise
  /// sigma the window's thinnest spread is sigma, so it can pass the flatness test only where its
  /// rows spread at least sigma / max_flatness across the beam. Where the three adjacent rows
  /// fail the test and spread less than that at the return's range (range * rowPitch *
  /// sqrt(2 / 3)), the window is three rows k apart, the return's own among them, for the least k
  /// that spreads enough, over k times the columns (still square in view angle), at most a quarter
  /// of the rows apart in all (k <= rows / 8); its plane is kept only when every one of its
  /// returns lies within the last gate of it along its ray (a grown window can hold a corner's
  /// other surface as a minority).
  /// With 2 cm and 0.3 a 64-laser sweep's adjacent rows spread enough beyond about 11 m, a
  /// VLP-16's beyond about 2.3 m. 0, the default: adjacent rows only. Sweeps: the range noise
  /// where `lidar.returns_normal_growth` is on (returnsRefineParams).
  double normal_noise_m = 0.0;
  /// The returns fix a direction the cells left free (returnsBasin) when their rounds reach their
  /// pose again from starts basin_offset_m either side of it along its weakest translation, each
  /// ending within basin_tolerance_m of it [m, > 0]. Sweeps: half the first gate (a surface moved
  /// that far still lies inside it) and the range noise (returnsRefineParams).
  double basin_offset_m = 0.15;
  double basin_tolerance_m = 0.02;
};

/// Throws gasp::Error naming the first parameter out of its range.
void validate(const ReturnsRefineParams& params);

/// A sweep's returns as a view keeps them for stage 7: each return's point in the sensor frame
/// and, where the returns around it lie on one flat surface, its normal (computed once, when the
/// view is made, so that a keyframe's serve every frame registered to it).
class SweepReturns {
 public:
  /// Throws gasp::Error for a scan that is not a range image (validateLayout) or invalid params.
  /// Keeps its own copy of the scan's images. Memory: 52 bytes per cell (the copy, a point and a
  /// normal), about 1.5 MB for a 16-laser sweep of 1800 columns, 6 MB for 64 lasers.
  SweepReturns(const RangeScan& scan, const ReturnsRefineParams& params);

  const RangeScan& scan() const { return scan_; }
  int rows() const { return rows_; }
  int cols() const { return cols_; }
  /// The return of cell (row, col) [m, sensor frame]; NaN where there is none.
  const Eigen::Vector3d& point(int row, int col) const { return point_[index(row, col)]; }
  /// The return with a normal nearest in direction to `q` (sensor frame): in the row of the
  /// nearest elevation, the nearest column within `reach` columns (a sweep may leave every other
  /// column empty, a dual-return VLP-16's does; across the seam of a whole turn). Its index for
  /// point(i) and normal(i), or -1.
  int lookUp(const Eigen::Vector3d& q, int reach) const;
  const Eigen::Vector3d& point(int i) const { return point_[static_cast<std::size_t>(i)]; }
  const Eigen::Vector3d& normal(int i) const { return normal_[static_cast<std::size_t>(i)]; }
  /// A point of the surface between the returns around `q` (sensor frame), for return i with a
  /// normal that q looked up: return i plus the offsets to its neighbours toward q in its column
  /// (the next row) and in its row (the next column) that lie within `tolerance` [m] of its plane,
  /// weighted by q's direction on theirs (the rays: no range noise), each weight in [0, 1]; return
  /// i itself where neither neighbour does. On a plane it lies on the plane near q, though not on
  /// q's ray (the weights are linear in the directions, the plane's map to them projective), so a
  /// point between two rows is compared with the surface measured there, not with return i's
  /// plane extended a row's spacing, where a normal's error would multiply that spacing.
  Eigen::Vector3d surfaceNear(int i, const Eigen::Vector3d& q, double tolerance) const;
  /// Half the diagonal of a cell [rad]: how far in angle a point can lie from the return it fell on.
  double halfCellRad() const { return half_cell_rad_; }
  /// The normal half-width (the effective one: squareNormalHalfWidth() for 0), flatness and noise
  /// the normals were fitted with.
  int normalHalfWidth() const { return normal_half_width_; }
  double maxFlatness() const { return max_flatness_; }
  double normalNoise() const { return normal_noise_m_; }
  /// The spacing in rows of the three rows of a grown window for a return at `range` [m]
  /// (normal_noise_m): 1 where adjacent rows spread enough.
  int windowRowSpacing(double range) const;
  /// How far from a return's plane a neighbour or a three-row window's return (along its ray) may
  /// lie and still be on it [m]: the rounds' last gate.
  double planeTolerance() const { return plane_tolerance_; }

 private:
  std::size_t index(int r, int c) const { return static_cast<std::size_t>(r) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(c); }
  /// Sums of points and of their outer products (a plane fit's moments).
  struct Moments {
    double n = 0.0;
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    Eigen::Matrix3d ss = Eigen::Matrix3d::Zero();
    void add(const Eigen::Vector3d& q) { n += 1.0, s += q, ss += q * q.transpose(); }
    void addDifference(const Moments& upper, const Moments& lower) {
      n += upper.n - lower.n, s += upper.s - lower.s, ss += upper.ss - lower.ss;
    }
  };
  Eigen::Vector3d fitNormal(int r, int c, const std::vector<Moments>& prefix) const;
  /// Adds the returns of `row` in columns [lo, hi] whose ranges lie within 0.1 m + 5 % of `range`
  /// to m; true when it added any.
  bool addRow(int row, int lo, int hi, float range, const std::vector<Moments>& prefix, Moments& m) const;

  RangeScan scan_;
  int rows_ = 0, cols_ = 0;
  bool whole_turn_ = false;
  double half_cell_rad_ = 0.0;
  int normal_half_width_ = 3;
  double max_flatness_ = 0.3;
  double normal_noise_m_ = 0.0;
  double row_pitch_rad_ = 0.0;
  int max_row_spacing_ = 1;  ///< a grown window's row spacing at most (rows / 8, at least 1)
  double plane_tolerance_ = 0.08;  ///< the rounds' last gate [m]
  std::vector<Eigen::Vector3d> point_, normal_;
};

/// The normal window's half-width in columns that is square in view angle: round(rowPitch /
/// |azimuthStep|), in [1, 100]. Throws gasp::Error for a scan that is not a range image.
int squareNormalHalfWidth(const RangeScan& scan);

/// One round's point-to-plane terms: each source point (sensor frame) mapped by T_target_source
/// takes the target's return of nearest direction with a normal (SweepReturns::lookUp within
/// look_up_columns) when that return is seen within max_incidence_deg, the point lies within `gate`
/// of the term's plane and within the gate plus a cell's footprint of the return across it. The
/// term's plane is the return's normal through the surface between the returns around the point
/// (SweepReturns::surfaceNear, the neighbours within target.planeTolerance() of the return's plane).
std::vector<PointToPlane> returnTerms(const std::vector<Eigen::Vector3d>& source_points, const SweepReturns& target,
                                      const Isometry3& T_target_source, double gate, int look_up_columns,
                                      double max_incidence_deg);

/// Refines T_target_source between the two sweeps (point-to-plane, the target's normals;
/// `solver`: loss, noise and degeneracy test; returns seen beyond max_incidence_deg give no term).
/// The target's normals are those it was made with (params' normal settings are not used again).
/// success false, with a reason, when fewer than 6 terms remain or a solve fails. Throws
/// gasp::Error for invalid params.
RegistrationResult refineOnReturns(const SweepReturns& source, const SweepReturns& target, const Isometry3& T_target_source,
                                   const ReturnsRefineParams& params = {}, const RefinementParams& solver = {},
                                   double max_incidence_deg = 80.0);
/// The same on two scans (their returns made with `params`).
RegistrationResult refineOnReturns(const RangeScan& source, const RangeScan& target, const Isometry3& T_target_source,
                                   const ReturnsRefineParams& params = {}, const RefinementParams& solver = {},
                                   double max_incidence_deg = 80.0);

/// Whether the returns' rounds fix their pose's weakest translation themselves, rather than keep
/// it where they started: the rounds run again from `pose` moved params.basin_offset_m either way
/// along the largest axis of its translation's covariance (the information's inverse), and both
/// must succeed and end within params.basin_tolerance_m of it (< basin_offset_m). On the simulated
/// room's pairs whose cells leave the sensor's vertical free, restarts of the rounds that end
/// right come back within 0.9 cm, and for the rounds that end wrong the farther restart ends
/// 15-88 cm away (docs/lidar.md "The returns fix what the cells leave free").
/// The weakest translation of a pose's information [t r]: the unit largest axis of the
/// translation's marginal covariance (the information's inverse; the rotation left free).
/// nullopt when the information is not positive definite.
std::optional<Eigen::Vector3d> weakestTranslation(const Matrix6d& information);

struct ReturnsBasin {
  bool held = false;
  double farthest_m = 0.0;  ///< the farther of the two restarts' ends from the pose (infinite: one failed)
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  ///< the weakest translation, target frame
  std::array<RegistrationResult, 2> ends;  ///< the restarts' results, from -offset and +offset
  std::string reason;  ///< why not, when it did not hold
};
ReturnsBasin returnsBasin(const SweepReturns& source, const SweepReturns& target, const RegistrationResult& pose,
                          const ReturnsRefineParams& params = {}, const RefinementParams& solver = {},
                          double max_incidence_deg = 80.0);

/// Where a point in a sweep's sensor frame lands on that sweep's returns: the return nearest its
/// direction with a normal (SweepReturns::lookUp, no reach), how far the point lies beyond the
/// plane a term would use (the return's normal through SweepReturns::surfaceNear's point) along the
/// point's ray, the incidence clamped at max_incidence_deg (negative: in front of it, in the space
/// the sweep saw empty), its distance from that plane, and the free-space gate there: 5 range_sigma_m plus the depth
/// change of the return's surface across half a cell (the incidence clamped at max_incidence_deg).
struct ReturnLanding {
  int index = -1;  ///< the return's (SweepReturns::point(i)); -1: it lands on none with a normal
  double beyond_m = 0.0, plane_m = 0.0, gate_m = 0.0;
};
ReturnLanding landOnReturns(const SweepReturns& sweep, const Eigen::Vector3d& q, double range_sigma_m,
                            double max_incidence_deg);

/// The free-space test (visibility_check.h) on the sweeps' own returns rather than on binned cells,
/// whose means of different returns in each sweep disagree 9 m apart even at the true pose: every
/// return of each sweep, mapped into the other, against the return nearest its direction there
/// (with a normal); consistent within 5 range_sigma_m plus the depth change of that return's
/// surface across half a cell (the incidence clamped at max_incidence_deg), occluded behind it,
/// a violation in front of it. `params`' limits (violations per direction and seen from both,
/// occlusion, consistent samples) decide as they do for the cells; its gates and steps are not
/// used.
VisibilityCheck returnsFreeSpace(const SweepReturns& source, const SweepReturns& target, const Isometry3& T_target_source,
                                 const VisibilityCheckParams& params, double range_sigma_m,
                                 double max_incidence_deg = 80.0);

}  // namespace gasp
