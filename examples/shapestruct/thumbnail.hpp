// SPDX-License-Identifier: MIT
// Thumbnails for `shapestruct analyze`'s report: a small z-buffer software rasteriser (flat shading, fixed
// orthographic camera) and a PNG writer on libpng. Deterministic: the same triangles give the same bytes.
// Part of the tool, not of the library's public headers.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <png.h>

#include <Eigen/Core>

#include "shapestruct/templates/collection_runner.hpp"

namespace shapestruct::cli {

using rgb = std::array<std::uint8_t, 3>;

/// An 8-bit RGB image, rows top to bottom.
struct rgb_image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  ///< width * height * 3
};

/// The part colours of `shapestruct templates`' PLY files, so the report's colours match them; a negative label
/// is dark grey.
inline rgb part_color(long label) { return detail::label_color(static_cast<index_t>(label)); }

/// Renders triangles (V rows are points in a frame whose +y is up and whose front faces -z, the generator's
/// convention) with flat shading from a fixed camera: 30 degrees to the front-left, 20 degrees above, orthographic,
/// the shape's bounding box fitted to the image. Both faces of a triangle are lit (soups have no orientation).
/// Rendered at 2x and box-filtered down. `face_colors` holds one colour per face.
inline rgb_image render_thumbnail(const Eigen::Matrix<double, Eigen::Dynamic, 3>& V,
                                  const Eigen::Matrix<long, Eigen::Dynamic, 3>& F, const std::vector<rgb>& face_colors,
                                  int size = 160) {
  const int ss = 2, W = size * ss, H = size * ss;
  // Camera: rotate about y by the azimuth, then tilt about x by the elevation; the camera looks along +z.
  const double az = 30.0 * M_PI / 180.0, el = 20.0 * M_PI / 180.0;
  Eigen::Matrix3d Ry, Rx;
  Ry << std::cos(az), 0, std::sin(az), 0, 1, 0, -std::sin(az), 0, std::cos(az);
  Rx << 1, 0, 0, 0, std::cos(el), -std::sin(el), 0, std::sin(el), std::cos(el);
  const Eigen::Matrix3d R = Rx * Ry;
  Eigen::Matrix<double, Eigen::Dynamic, 3> P(V.rows(), 3);
  for (Eigen::Index i = 0; i < V.rows(); ++i) P.row(i) = (R * V.row(i).transpose()).transpose();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    if (!P.row(i).allFinite()) continue;
    lo = lo.cwiseMin(P.row(i).transpose());
    hi = hi.cwiseMax(P.row(i).transpose());
  }
  rgb_image big{W, H, std::vector<std::uint8_t>(std::size_t(W) * std::size_t(H) * 3, 255)};
  if (!(hi.x() >= lo.x())) return big;  // no finite vertex: blank (callers check)
  const double extent = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-12});
  const double scale = 0.9 * double(W) / extent;
  const double cx = 0.5 * (lo.x() + hi.x()), cy = 0.5 * (lo.y() + hi.y());
  auto to_screen = [&](const Eigen::Vector3d& p) {
    // x to the right, y up on screen (so image row = H/2 - y), depth: smaller z is nearer (camera looks along +z).
    return Eigen::Vector3d(0.5 * W + (p.x() - cx) * scale, 0.5 * H - (p.y() - cy) * scale, p.z());
  };
  std::vector<double> depth(std::size_t(W) * std::size_t(H), std::numeric_limits<double>::infinity());
  const Eigen::Vector3d light = Eigen::Vector3d(-0.4, 0.6, -0.7).normalized();  // in camera space
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = P.row(F(f, 0)).transpose(), b = P.row(F(f, 1)).transpose(), c = P.row(F(f, 2)).transpose();
    if (!a.allFinite() || !b.allFinite() || !c.allFinite()) continue;
    Eigen::Vector3d n = (b - a).cross(c - a);
    const double nn = n.norm();
    if (!(nn > 0)) continue;
    n /= nn;
    const double shade = 0.3 + 0.7 * std::abs(n.dot(light));
    const rgb base = face_colors[std::size_t(f)];
    const std::array<std::uint8_t, 3> col = {static_cast<std::uint8_t>(std::lround(base[0] * shade)),
                                             static_cast<std::uint8_t>(std::lround(base[1] * shade)),
                                             static_cast<std::uint8_t>(std::lround(base[2] * shade))};
    const Eigen::Vector3d A = to_screen(a), B = to_screen(b), C = to_screen(c);
    const double area = (B.x() - A.x()) * (C.y() - A.y()) - (B.y() - A.y()) * (C.x() - A.x());
    if (std::abs(area) < 1e-12) continue;
    const int x0 = std::max(0, int(std::floor(std::min({A.x(), B.x(), C.x()}))));
    const int x1 = std::min(W - 1, int(std::ceil(std::max({A.x(), B.x(), C.x()}))));
    const int y0 = std::max(0, int(std::floor(std::min({A.y(), B.y(), C.y()}))));
    const int y1 = std::min(H - 1, int(std::ceil(std::max({A.y(), B.y(), C.y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        const double w0 = ((B.x() - px) * (C.y() - py) - (B.y() - py) * (C.x() - px)) / area;
        const double w1 = ((C.x() - px) * (A.y() - py) - (C.y() - py) * (A.x() - px)) / area;
        const double w2 = 1.0 - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const double z = w0 * A.z() + w1 * B.z() + w2 * C.z();
        const std::size_t k = std::size_t(y) * std::size_t(W) + std::size_t(x);
        if (z >= depth[k]) continue;
        depth[k] = z;
        std::copy(col.begin(), col.end(), big.pixels.begin() + std::ptrdiff_t(3 * k));
      }
  }
  rgb_image out{size, size, std::vector<std::uint8_t>(std::size_t(size) * std::size_t(size) * 3)};
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (int ch = 0; ch < 3; ++ch) {
        int sum = 0;
        for (int dy = 0; dy < ss; ++dy)
          for (int dx = 0; dx < ss; ++dx)
            sum += big.pixels[3 * (std::size_t(y * ss + dy) * std::size_t(W) + std::size_t(x * ss + dx)) + std::size_t(ch)];
        out.pixels[3 * (std::size_t(y) * std::size_t(size) + std::size_t(x)) + std::size_t(ch)] =
            static_cast<std::uint8_t>((sum + ss * ss / 2) / (ss * ss));
      }
  return out;
}

/// True when every pixel has the same colour.
inline bool is_blank(const rgb_image& im) {
  for (std::size_t i = 3; i < im.pixels.size(); ++i)
    if (im.pixels[i] != im.pixels[i % 3]) return false;
  return true;
}

/// Writes an 8-bit RGB PNG (no time or text chunks: the bytes depend on the pixels only), atomically
/// (temporary file + rename). \throws std::runtime_error naming the path.
inline void write_png(const std::filesystem::path& path, const rgb_image& im) {
  const std::string tmp = path.string() + ".tmp";
  FILE* fp = std::fopen(tmp.c_str(), "wb");
  if (!fp) throw std::runtime_error(tmp + ": cannot open for writing");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, nullptr);
    std::fclose(fp);
    throw std::runtime_error(tmp + ": libpng could not start");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(fp);
    throw std::runtime_error(tmp + ": libpng failed to write");
  }
  png_init_io(png, fp);
  png_set_IHDR(png, info, png_uint_32(im.width), png_uint_32(im.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < im.height; ++y)
    png_write_row(png, im.pixels.data() + std::size_t(y) * std::size_t(im.width) * 3);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(fp) != 0) throw std::runtime_error(tmp + ": could not write the whole file");
  std::filesystem::rename(tmp, path);
}

}  // namespace shapestruct::cli
