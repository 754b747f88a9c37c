// SPDX-License-Identifier: MIT
// collection_files: the binary files a collection run caches (shape records, pairwise alignments) for resuming.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "shapestruct/collection/pair_alignment.hpp"
#include "shapestruct/collection/shape_record.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/io/file_bytes.hpp"

namespace shapestruct {

namespace detail {

/// Little binary writer / reader of plain values and arrays (host byte order: the cache is a machine-local
/// resume aid, not an exchange format; the documented outputs are text).
class binary_writer {
 public:
  template <class T>
    requires std::is_trivially_copyable_v<T>
  void put(const T& v) {
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <class T>
  void put_array(const T* p, std::size_t n) {
    put<std::uint64_t>(n);
    bytes_.append(reinterpret_cast<const char*>(p), n * sizeof(T));
  }
  void put_string(std::string_view s) { put_array(s.data(), s.size()); }
  [[nodiscard]] const std::string& bytes() const noexcept { return bytes_; }

 private:
  std::string bytes_;
};

class binary_reader {
 public:
  binary_reader(std::string_view bytes, std::string path) : bytes_(bytes), path_(std::move(path)) {}
  template <class T>
    requires std::is_trivially_copyable_v<T>
  T get() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  template <class T>
  std::vector<T> get_array() {
    const auto n = get<std::uint64_t>();
    if (n > bytes_.size()) fail("array length beyond the end of the file");
    need(n * sizeof(T));
    std::vector<T> v(n);
    if (n) std::memcpy(v.data(), bytes_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
    return v;
  }
  std::string get_string() {
    const auto v = get_array<char>();
    return std::string(v.begin(), v.end());
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw io_error(file_error::syntax, path_, 0, static_cast<std::int64_t>(at_), "damaged cache file: " + what);
  }

 private:
  void need(std::size_t n) const {
    if (at_ + n > bytes_.size()) fail("ends early");
  }
  std::string_view bytes_;
  std::string path_;
  std::size_t at_ = 0;
};

inline constexpr std::uint32_t record_magic = 0x52535353;     // "SSSR"
inline constexpr std::uint32_t alignment_magic = 0x41535353;  // "SSSA"
inline constexpr std::uint32_t collection_file_version = 1;
inline constexpr std::uint32_t alignment_file_version = 3;  // 2: the aligner's preferred alternative; 3: blended
// maps from at least blended_shape_options::min_features features (intrinsic alignments made before differ)

template <class M>
void put_matrix(binary_writer& w, const M& m) {
  w.put<std::int64_t>(m.rows());
  w.put<std::int64_t>(m.cols());
  w.put_array(m.data(), static_cast<std::size_t>(m.size()));
}
template <class M>
M get_matrix(binary_reader& r) {
  const auto rows = r.get<std::int64_t>();
  const auto cols = r.get<std::int64_t>();
  const auto data = r.get_array<typename M::Scalar>();
  if (rows < 0 || cols < 0 || static_cast<std::size_t>(rows * cols) != data.size()) r.fail("matrix size");
  M m(rows, cols);
  if (!data.empty()) std::memcpy(m.data(), data.data(), data.size() * sizeof(typename M::Scalar));
  return m;
}

}  // namespace detail

/// Writes a shape record atomically. \throws io_error (cannot_open, write_failed).
inline void write_shape_record(const std::filesystem::path& path, const shape_record& r) {
  detail::binary_writer w;
  w.put(detail::record_magic);
  w.put(detail::collection_file_version);
  w.put_string(r.name);
  detail::put_matrix(w, r.samples);
  w.put_array(r.sample_vertex.data(), r.sample_vertex.size());
  w.put_array(r.vertex_sample.data(), r.vertex_sample.size());
  detail::put_matrix(w, r.surface_points);
  detail::put_matrix(w, r.sample_geodesics);
  detail::put_matrix(w, r.descriptor);
  w.put(r.diameter);
  w.put(r.area);
  w.put<std::uint8_t>(r.closed_genus0 ? 1 : 0);
  w.put<std::int64_t>(r.vertex_count);
  io_detail::write_file_atomically(path, w.bytes());
}

/// Reads a shape record written by write_shape_record. \throws io_error (cannot_open, syntax for a damaged file).
[[nodiscard]] inline shape_record read_shape_record(const std::filesystem::path& path) {
  const std::string bytes = io_detail::read_file_bytes(path);
  detail::binary_reader rd(bytes, path.string());
  if (rd.get<std::uint32_t>() != detail::record_magic) rd.fail("not a shape record");
  if (rd.get<std::uint32_t>() != detail::collection_file_version) rd.fail("written by another version");
  shape_record r;
  r.name = rd.get_string();
  r.samples = detail::get_matrix<Eigen::Matrix<double, Eigen::Dynamic, 3>>(rd);
  r.sample_vertex = rd.get_array<index_t>();
  r.vertex_sample = rd.get_array<std::int32_t>();
  r.surface_points = detail::get_matrix<Eigen::Matrix<double, Eigen::Dynamic, 3>>(rd);
  r.sample_geodesics = detail::get_matrix<Eigen::MatrixXf>(rd);
  r.descriptor = detail::get_matrix<Eigen::VectorXd>(rd);
  r.diameter = rd.get<double>();
  r.area = rd.get<double>();
  r.closed_genus0 = rd.get<std::uint8_t>() != 0;
  r.vertex_count = rd.get<std::int64_t>();
  return r;
}

/// Writes a pairwise alignment atomically (every alternative with its sparse scores).
/// \throws io_error (cannot_open, write_failed).
inline void write_pair_alignment(const std::filesystem::path& path, const pair_alignment& a) {
  detail::binary_writer w;
  w.put(detail::alignment_magic);
  w.put(detail::alignment_file_version);
  w.put<std::int64_t>(a.source);
  w.put<std::int64_t>(a.target);
  w.put<std::int64_t>(a.initial);
  w.put<std::int64_t>(a.preferred);
  w.put(a.seconds);
  w.put<std::uint64_t>(a.alternatives.size());
  for (const auto& alt : a.alternatives) {
    w.put(alt.global_score);
    w.put_array(alt.parameters.data(), alt.parameters.size());
    auto s = alt.scores;
    s.makeCompressed();
    w.put<std::int64_t>(s.rows());
    w.put<std::int64_t>(s.cols());
    w.put_array(s.outerIndexPtr(), static_cast<std::size_t>(s.outerSize() + 1));
    w.put_array(s.innerIndexPtr(), static_cast<std::size_t>(s.nonZeros()));
    w.put_array(s.valuePtr(), static_cast<std::size_t>(s.nonZeros()));
  }
  io_detail::write_file_atomically(path, w.bytes());
}

/// Reads a pairwise alignment written by write_pair_alignment.
/// \throws io_error (cannot_open, syntax for a damaged file).
[[nodiscard]] inline pair_alignment read_pair_alignment(const std::filesystem::path& path) {
  const std::string bytes = io_detail::read_file_bytes(path);
  detail::binary_reader rd(bytes, path.string());
  if (rd.get<std::uint32_t>() != detail::alignment_magic) rd.fail("not a pairwise alignment");
  if (rd.get<std::uint32_t>() != detail::alignment_file_version) rd.fail("written by another version");
  pair_alignment a;
  a.source = rd.get<std::int64_t>();
  a.target = rd.get<std::int64_t>();
  a.initial = rd.get<std::int64_t>();
  a.preferred = rd.get<std::int64_t>();
  a.seconds = rd.get<double>();
  const auto n = rd.get<std::uint64_t>();
  if (n > bytes.size()) rd.fail("alternative count");
  a.alternatives.resize(n);
  for (auto& alt : a.alternatives) {
    alt.global_score = rd.get<double>();
    alt.parameters = rd.get_array<double>();
    const auto rows = rd.get<std::int64_t>();
    const auto cols = rd.get<std::int64_t>();
    const auto outer = rd.get_array<std::int32_t>();
    const auto inner = rd.get_array<std::int32_t>();
    const auto values = rd.get_array<float>();
    if (rows < 0 || cols < 0 || outer.size() != static_cast<std::size_t>(rows + 1) || inner.size() != values.size() ||
        outer.back() != static_cast<std::int32_t>(values.size()))
      rd.fail("sparse matrix layout");
    for (const auto c : inner)
      if (c < 0 || c >= cols) rd.fail("column index out of range");
    alt.scores.resize(rows, cols);
    alt.scores.reserve(static_cast<index_t>(values.size()));
    for (std::int64_t r = 0; r < rows; ++r) {
      alt.scores.startVec(r);
      for (auto k = outer[std::size_t(r)]; k < outer[std::size_t(r + 1)]; ++k)
        alt.scores.insertBack(r, inner[std::size_t(k)]) = values[std::size_t(k)];
    }
    alt.scores.finalize();
  }
  if (a.initial < 0 || (n > 0 && a.initial >= static_cast<index_t>(n))) rd.fail("initial alternative");
  if (a.preferred != no_index && (a.preferred < 0 || a.preferred >= static_cast<index_t>(n))) rd.fail("preferred alternative");
  return a;
}

}  // namespace shapestruct
