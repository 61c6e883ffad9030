// Lane surfaces of one lane section: a grid of rows (the s samples) by border columns, with
// border vertices shared between neighbouring lanes, curb faces where lane heights differ, and
// extra columns inside lanes on roads with a lateral shape.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "mesh_builder.h"

namespace corsa::xodr::detail {
namespace {

/// Narrower stretches of a lane (m) make no triangle: a lane that opens or closes (width 0 at one
/// end) gets a single triangle there, and a zero-width lane none.
constexpr double kMinWidth = 1e-6;
/// Lane heights closer than this (m) across a border count as equal (one shared vertex).
constexpr double kSameHeight = 1e-6;
/// Border vertices of consecutive sections closer than this (m) are shared.
constexpr double kSeamWeld = 1e-3;
/// Most columns per lane on roads with a lateral shape.
constexpr int kMaxColumns = 64;

/// Column counts per lane: 1, or more on roads with a lateral shape (§8.4.3), enough for the
/// cross-section to stay within the tolerance of its straight pieces on every row.
std::vector<int> lane_columns(const SectionView& view, const SectionSamples& samples,
                              double tolerance) {
  std::vector<int> columns(view.lanes(), 1);
  if (!view.has_shape()) {
    return columns;
  }
  for (size_t r = 0; r < samples.rows(); ++r) {
    const RoadFrame& f = samples.frames[r];
    const double* t = samples.row_t(r);
    for (size_t i = 0; i < view.lanes(); ++i) {
      const auto fits = [&](int c) {
        for (int k = 0; k < c; ++k) {
          const double ta = t[i] + (t[i + 1] - t[i]) * k / c;
          const double tb = t[i] + (t[i + 1] - t[i]) * (k + 1) / c;
          const double middle = 0.5 * (view.surface(f, ta).z + view.surface(f, tb).z);
          if (std::abs(view.surface(f, 0.5 * (ta + tb)).z - middle) > tolerance) {
            return false;
          }
        }
        return true;
      };
      while (columns[i] < kMaxColumns && !fits(columns[i])) {
        columns[i] *= 2;
      }
    }
  }
  return columns;
}

class SectionMesher {
 public:
  SectionMesher(const SectionView& view, const SectionSamples& samples, MeshBuilder& builder,
                double tolerance)
      : view_(view), samples_(samples), builder_(builder), n_(view.lanes()) {
    columns_ = lane_columns(view, samples, tolerance);
    offsets_.resize(n_ + 1, 0);
    for (size_t i = 0; i < n_; ++i) {
      offsets_[i + 1] = offsets_[i] + static_cast<size_t>(columns_[i]) + 1;
    }
    stride_ = offsets_[n_];
    split_.assign(n_ + 1, false);
    heights_.resize(samples.rows() * 2 * n_);
    for (size_t r = 0; r < samples.rows(); ++r) {
      for (size_t i = 0; i < n_; ++i) {
        height(r, i, true) = view.lane_height(i, samples.s[r], true);
        height(r, i, false) = view.lane_height(i, samples.s[r], false);
      }
      for (size_t j = 1; j < n_; ++j) {
        split_[j] =
            split_[j] || std::abs(height(r, j - 1, false) - height(r, j, true)) > kSameHeight;
      }
    }
    vertices_.resize(samples.rows() * stride_);
  }

  void run(std::vector<SeamVertex>& seam) {
    if (n_ == 0 || samples_.rows() < 2) {
      seam.clear();
      return;
    }
    for (size_t r = 0; r < samples_.rows(); ++r) {
      make_row(r, r == 0 ? &seam : nullptr);
    }
    std::vector<SeamVertex> last;
    make_seam(samples_.rows() - 1, last);
    for (size_t r = 0; r + 1 < samples_.rows(); ++r) {
      for (size_t i = 0; i < n_; ++i) {
        lane_quads(r, i);
      }
      for (size_t j = 1; j < n_; ++j) {
        if (split_[j]) {
          curb_face(r, j);
        }
      }
    }
    seam = std::move(last);
  }

 private:
  double& height(size_t r, size_t i, bool left) {
    return heights_[(r * n_ + i) * 2 + (left ? 0 : 1)];
  }
  uint32_t& column(size_t r, size_t i, size_t k) {
    return vertices_[r * stride_ + offsets_[i] + k];
  }
  /// t of column k of lane i on row r.
  double column_t(size_t r, size_t i, size_t k) const {
    const double* t = samples_.row_t(r);
    return t[i] + (t[i + 1] - t[i]) * static_cast<double>(k) / columns_[i];
  }

  /// The vertex of border t on the current row: the previous border's when a zero-width lane
  /// lies between them (so that its neighbours share an edge), the previous section's on the
  /// seam, else a new one.
  uint32_t make_vertex(const RoadFrame& f, double t, double h, double across,
                       const std::vector<SeamVertex>* seam) {
    if (last_.valid && std::abs(t - last_.t) <= kMinWidth &&
        std::abs(h - last_.height) <= kSameHeight) {
      return last_.index;
    }
    Vec3 p = view_.surface(f, t);
    p.z += h;
    uint32_t index = UINT32_MAX;
    if (seam != nullptr) {
      for (const SeamVertex& v : *seam) {
        const double d = std::hypot(v.p.x - p.x, v.p.y - p.y, v.p.z - p.z);
        if (d <= kSeamWeld && std::abs(v.height - h) <= kSameHeight) {
          index = v.index;
          break;
        }
      }
    }
    if (index == UINT32_MAX) {
      index = builder_.add_vertex(p, {static_cast<float>(f.s), static_cast<float>(across)});
    }
    last_ = LastVertex{true, t, h, index};
    return index;
  }

  /// Lane coordinate across (RoadMesh::lane_coords) of lane i's left (`left` true) or right
  /// border: a left lane (id > 0) has its outer border on its left, a right lane on its right.
  double border_across(size_t i, bool left) const {
    const int id = view_.lane(i).id;
    const double outer = std::abs(id);
    return (id > 0) == left ? outer : outer - 1.0;
  }

  void make_row(size_t r, const std::vector<SeamVertex>* seam) {
    const RoadFrame& f = samples_.frames[r];
    const double* t = samples_.row_t(r);
    last_ = LastVertex{};
    for (size_t j = 0; j <= n_; ++j) {
      const bool has_left_lane = j > 0;  // lane j - 1 ends at border j on its right
      const bool has_right_lane = j < n_;
      if (has_left_lane && has_right_lane && !split_[j]) {
        const uint32_t v =
            make_vertex(f, t[j], height(r, j - 1, false), border_across(j, true), seam);
        column(r, j - 1, static_cast<size_t>(columns_[j - 1])) = v;
        column(r, j, 0) = v;
        continue;
      }
      if (has_left_lane) {
        column(r, j - 1, static_cast<size_t>(columns_[j - 1])) =
            make_vertex(f, t[j], height(r, j - 1, false), border_across(j - 1, false), seam);
      }
      if (has_right_lane) {
        column(r, j, 0) = make_vertex(f, t[j], height(r, j, true), border_across(j, true), seam);
      }
    }
    last_ = LastVertex{};
    for (size_t i = 0; i < n_; ++i) {
      for (int k = 1; k < columns_[i]; ++k) {
        const double w = static_cast<double>(k) / columns_[i];
        const double h = height(r, i, true) + w * (height(r, i, false) - height(r, i, true));
        const double across =
            border_across(i, true) + w * (border_across(i, false) - border_across(i, true));
        column(r, i, static_cast<size_t>(k)) =
            make_vertex(f, column_t(r, i, static_cast<size_t>(k)), h, across, nullptr);
      }
    }
  }

  void make_seam(size_t r, std::vector<SeamVertex>& out) {
    for (size_t i = 0; i < n_; ++i) {
      const uint32_t left = column(r, i, 0);
      const uint32_t right = column(r, i, static_cast<size_t>(columns_[i]));
      out.push_back(SeamVertex{builder_.vertex(left), height(r, i, true), left});
      out.push_back(SeamVertex{builder_.vertex(right), height(r, i, false), right});
    }
  }

  TriangleInfo lane_info(size_t i) const {
    TriangleInfo info;
    info.road_index = view_.road_index();
    info.lane_id = view_.lane(i).id;
    info.lane_type = view_.lane(i).type;
    info.in_junction = view_.road().in_junction();
    return info;
  }

  /// Two triangles per column between rows r and r + 1, counter-clockwise from above: with s
  /// forward and t to the left, R(r) -> R(r+1) -> L(r+1) -> L(r) runs counter-clockwise.
  void lane_quads(size_t r, size_t i) {
    const TriangleInfo info = lane_info(i);
    const double s = samples_.s[r];
    // Between the two limits of a jump a kink's wedge fills the outer side of the turn; its
    // inner side faces down and a sideways jump makes slivers: both are dropped silently.
    const Road* fold_road = samples_.is_jump(r) ? nullptr : &view_.road();
    for (size_t k = 0; k < static_cast<size_t>(columns_[i]); ++k) {
      const uint32_t left0 = column(r, i, k);
      const uint32_t right0 = column(r, i, k + 1);
      const uint32_t left1 = column(r + 1, i, k);
      const uint32_t right1 = column(r + 1, i, k + 1);
      if (column_t(r + 1, i, k) - column_t(r + 1, i, k + 1) > kMinWidth) {
        builder_.add_upward(right0, right1, left1, info, fold_road, s);
      }
      if (column_t(r, i, k) - column_t(r, i, k + 1) > kMinWidth) {
        builder_.add_upward(right0, left1, left0, info, fold_road, s);
      }
    }
  }

  /// The vertical face between lane j - 1 and lane j at border j where their heights differ,
  /// facing the lower lane and labelled as the raised one (a curb's side).
  void curb_face(size_t r, size_t j) {
    const uint32_t a0 = column(r, j - 1, static_cast<size_t>(columns_[j - 1]));
    const uint32_t a1 = column(r + 1, j - 1, static_cast<size_t>(columns_[j - 1]));
    const uint32_t b0 = column(r, j, 0);
    const uint32_t b1 = column(r + 1, j, 0);
    const double rise0 = height(r, j, true) - height(r, j - 1, false);
    const double rise1 = height(r + 1, j, true) - height(r + 1, j - 1, false);
    const bool right_raised = rise0 + rise1 > 0.0;
    const TriangleInfo info = lane_info(right_raised ? j : j - 1);
    // Towards the lower lane: +t (left) when the right lane is the raised one.
    const RoadFrame& f = samples_.frames[r];
    const double side = right_raised ? 1.0 : -1.0;
    const double toward_x = -f.sin_h * side;
    const double toward_y = f.cos_h * side;
    const auto add = [&](uint32_t p, uint32_t q, uint32_t u) {
      const Vec3& vp = builder_.vertex(p);
      const Vec3& vq = builder_.vertex(q);
      const Vec3& vu = builder_.vertex(u);
      const double e1x = vq.x - vp.x, e1y = vq.y - vp.y, e1z = vq.z - vp.z;
      const double e2x = vu.x - vp.x, e2y = vu.y - vp.y, e2z = vu.z - vp.z;
      const double nx = e1y * e2z - e1z * e2y;
      const double ny = e1z * e2x - e1x * e2z;
      if (nx * toward_x + ny * toward_y >= 0.0) {
        builder_.add_any(p, q, u, info);
      } else {
        builder_.add_any(p, u, q, info);
      }
    };
    if (std::abs(rise1) > kSameHeight) {
      add(a0, a1, b1);
    }
    if (std::abs(rise0) > kSameHeight) {
      add(a0, b1, b0);
    }
  }

  struct LastVertex {
    bool valid = false;
    double t = 0.0;
    double height = 0.0;
    uint32_t index = 0;
  };

  const SectionView& view_;
  const SectionSamples& samples_;
  MeshBuilder& builder_;
  LastVertex last_;
  size_t n_ = 0;
  std::vector<int> columns_;
  std::vector<size_t> offsets_;
  size_t stride_ = 0;
  std::vector<bool> split_;
  std::vector<double> heights_;
  std::vector<uint32_t> vertices_;
};

}  // namespace

void mesh_section_lanes(const SectionView& view, const SectionSamples& samples, double tolerance,
                        MeshBuilder& builder, std::vector<SeamVertex>& seam) {
  SectionMesher mesher(view, samples, builder, tolerance);
  mesher.run(seam);
}

}  // namespace corsa::xodr::detail
