#include "arrays.h"

#include <Eigen/Dense>

#include <cmath>
#include <cstdint>
#include <limits>
#include <new>

#include "gasp/core/depth_image.h"

namespace gasp::python {

std::string dtypeName(const py::array& array) { return py::str(array.dtype()).cast<std::string>(); }

std::string shapeText(const py::array& array) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) s += (i ? ", " : "") + std::to_string(array.shape(i));
  return s + (array.ndim() == 1 ? ",)" : ")");
}

namespace {

py::array asArray(const py::handle& h, const std::string& what) {
  if (!py::isinstance<py::array>(h))
    throw py::type_error(what + ": expected a numpy array, got " +
                         py::str(py::type::of(h).attr("__name__")).cast<std::string>());
  return py::reinterpret_borrow<py::array>(h);
}

/// Float depth [m] copied into `out` (CV_32FC1), refusing NaN, infinities and negative values.
template <class T>
void copyMetres(const py::array& array, cv::Mat& out, const std::string& what) {
  const auto a = py::array_t<T, py::array::c_style>::ensure(array);  // a copy only when strided
  if (!a) throw std::bad_alloc();  // ensure() clears its error: the copy could not be allocated (MemoryError)
  const T* data = a.data();
  std::size_t nan = 0, inf = 0, negative = 0, too_far = 0;
  const auto n = static_cast<std::size_t>(a.size());
  for (std::size_t i = 0; i < n; ++i) {
    const double d = static_cast<double>(data[i]);
    if (std::isnan(d)) ++nan;
    else if (std::isinf(d)) ++inf;
    else if (d < 0) ++negative;
    else if (d > static_cast<double>(std::numeric_limits<float>::max())) ++too_far;
  }
  const auto refuse = [&](std::size_t count, const std::string& kind) {
    if (count)
      throw py::value_error(what + ": " + std::to_string(count) + " " + kind +
                            " value(s); depth in metres must be finite and >= 0 (0 marks a pixel without depth)");
  };
  refuse(nan, "NaN"), refuse(inf, "infinite"), refuse(negative, "negative"), refuse(too_far, "beyond float32's range");
  float* o = out.ptr<float>();
  for (std::size_t i = 0; i < n; ++i) o[i] = static_cast<float>(data[i]);
}

}  // namespace

cv::Mat depthFromArray(const py::handle& handle, const CameraIntrinsics& intrinsics, double units_per_metre,
                       const std::string& what) {
  const py::array array = asArray(handle, what);
  if (array.ndim() != 2)
    throw py::value_error(what + ": expected a 2-D array (height, width), got shape " + shapeText(array));
  if (array.shape(0) != intrinsics.height || array.shape(1) != intrinsics.width)
    throw py::value_error(what + ": shape " + shapeText(array) + " does not match the intrinsics' (height, width) = (" +
                          std::to_string(intrinsics.height) + ", " + std::to_string(intrinsics.width) + ")");
  cv::Mat depth(intrinsics.height, intrinsics.width, CV_32FC1);
  // isinstance<array_t<T>>: numpy's equivalence of dtypes (a pickled array's dtype is another object).
  if (py::isinstance<py::array_t<std::uint16_t>>(array)) {
    if (!(units_per_metre > 0) || !std::isfinite(units_per_metre))
      throw py::value_error(what + ": depth_units_per_metre must be positive and finite, got " +
                            std::to_string(units_per_metre));
    const auto a = py::array_t<std::uint16_t, py::array::c_style>::ensure(array);
    if (!a) throw std::bad_alloc();  // ensure() clears its error: the copy could not be allocated (MemoryError)
    const cv::Mat raw(intrinsics.height, intrinsics.width, CV_16UC1, const_cast<std::uint16_t*>(a.data()));
    cv::Mat metres = depthFromRaw(raw, units_per_metre);  // a new matrix: the array is not kept
    if (!cv::checkRange(metres))
      throw py::value_error(what + ": depth_units_per_metre " + py::repr(py::float_(units_per_metre)).cast<std::string>() +
                            " makes depths beyond float32's range");
    return metres;
  }
  if (py::isinstance<py::array_t<float>>(array)) copyMetres<float>(array, depth, what);
  else if (py::isinstance<py::array_t<double>>(array)) copyMetres<double>(array, depth, what);
  else
    throw py::type_error(what + ": dtype " + dtypeName(array) +
                         "; expected uint16 (raw units, depth_units_per_metre per metre) or float32 / float64 (metres)");
  return depth;
}

Isometry3 poseFromArray(const py::handle& handle, const std::string& what) {
  const py::array array = asArray(handle, what);
  if (array.ndim() != 2 || array.shape(0) != 4 || array.shape(1) != 4)
    throw py::value_error(what + ": expected a 4x4 array, got shape " + shapeText(array));
  if (!py::isinstance<py::array_t<double>>(array) && !py::isinstance<py::array_t<float>>(array))
    throw py::type_error(what + ": dtype " + dtypeName(array) + "; expected float64 or float32");
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!a) throw std::bad_alloc();  // ensure() clears its error: the copy could not be allocated (MemoryError)
  const auto v = a.unchecked<2>();
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      if (!std::isfinite(v(r, c))) throw py::value_error(what + ": a value is not finite");
      m(r, c) = v(r, c);
    }
  if (m.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) throw py::value_error(what + ": the last row must be 0 0 0 1");
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  if ((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 || R.determinant() < 0)
    throw py::value_error(what + ": the 3x3 block is not a rotation (orthonormal within 1e-6, determinant +1)");
  Isometry3 T = Isometry3::Identity();
  T.matrix() = m;
  return T;
}

py::array_t<double> poseArray(const Isometry3& T) { return matrixArray(T.matrix()); }

}  // namespace gasp::python
