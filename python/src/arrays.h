#pragma once
/// \file arrays.h numpy arrays in and out of the module: what Python hands GASP is checked here
/// (dtype, shape, finite values) and refused with a TypeError or ValueError naming the argument.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <opencv2/core.hpp>

#include <string>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/pose.h"

namespace gasp::python {

namespace py = pybind11;

/// A depth image from Python, in metres (CV_32FC1, 0 = no data, a copy): a uint16 array of raw
/// units divided by `units_per_metre`, or a float32 / float64 array of metres. The array must be
/// 2-D of the intrinsics' height x width; float values must be finite and not negative (0 marks a
/// pixel without depth). `what` names the argument in the messages ("source depth").
cv::Mat depthFromArray(const py::handle& array, const CameraIntrinsics& intrinsics, double units_per_metre,
                       const std::string& what);

/// A rigid transform from Python: a 4x4 array of finite numbers whose last row is 0 0 0 1 and
/// whose 3x3 block is a rotation (orthonormal within 1e-6, determinant +1).
Isometry3 poseFromArray(const py::handle& array, const std::string& what);

/// A 4x4 float64 array of the transform.
py::array_t<double> poseArray(const Isometry3& T);

/// A float64 array of an Eigen matrix's values, row-major, of shape (rows, cols).
template <class Matrix>
py::array_t<double> matrixArray(const Matrix& m) {
  py::array_t<double> out({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  auto o = out.mutable_unchecked<2>();
  for (py::ssize_t r = 0; r < o.shape(0); ++r)
    for (py::ssize_t c = 0; c < o.shape(1); ++c) o(r, c) = m(r, c);
  return out;
}

/// A (rows, cols) array copy of a single-channel image whose elements are T (CV_32S: int32,
/// CV_32F: float).
template <class T>
py::array_t<T> imageArray(const cv::Mat& image) {
  py::array_t<T> out({static_cast<py::ssize_t>(image.rows), static_cast<py::ssize_t>(image.cols)});
  auto o = out.template mutable_unchecked<2>();
  for (int r = 0; r < image.rows; ++r)
    for (int c = 0; c < image.cols; ++c) o(r, c) = image.at<T>(r, c);
  return out;
}

/// The numpy dtype's name, for messages ("int32", ">u2").
std::string dtypeName(const py::array& array);

/// "(480, 640)".
std::string shapeText(const py::array& array);

}  // namespace gasp::python
