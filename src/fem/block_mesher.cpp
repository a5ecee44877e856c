#include "fem/block_mesher.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace peensim {

std::vector<double> graded_axis(double length, double fine, double h, double growth) {
    if (!(length > 0.0) || !(h > 0.0) || !(growth >= 1.0) || !(fine >= 0.0))
        throw std::invalid_argument("graded_axis: length and element size must be positive and growth >= 1");
    fine = std::min(fine, length);
    std::vector<double> xs{0.0};
    const int n_fine = static_cast<int>(std::ceil(fine / h - 1e-9));
    for (int i = 1; i <= n_fine; ++i) xs.push_back(fine * i / n_fine);
    if (length - fine <= 1e-12 * length) {
        xs.back() = length;
        if (xs.size() == 1) xs.push_back(length);
        return xs;
    }
    // Coarse part: edges h g, h g^2, ... summing to at least the rest; scaled to end at `length`.
    const double rest = length - fine;
    std::vector<double> edges;
    double sum = 0.0, edge = n_fine > 0 ? fine / n_fine : h;
    while (sum < rest) {
        edge *= growth;
        edges.push_back(edge);
        sum += edge;
    }
    // Dropping the last edge when the sum overshoots by most of it keeps edges close to the progression.
    if (edges.size() > 1 && sum - rest > 0.5 * edges.back()) {
        sum -= edges.back();
        edges.pop_back();
    }
    const double scale = rest / sum;
    double x = fine;
    for (double e : edges) {
        x += e * scale;
        xs.push_back(x);
    }
    xs.back() = length;
    return xs;
}

double block_element_count(const BlockMeshSpec& spec) {
    if (!(spec.half_width_m > 0.0) || !(spec.depth_m > 0.0) || !(spec.element_size_m > 0.0))
        throw std::invalid_argument("mesh_block: block sizes and element size must be positive");
    const double half =
        static_cast<double>(graded_axis(spec.half_width_m, spec.fine_half_width_m, spec.element_size_m, spec.growth).size() - 1);
    const double depth = static_cast<double>(graded_axis(spec.depth_m, spec.fine_depth_m, spec.element_size_m, spec.growth).size() - 1);
    const double across = spec.quarter ? half : 2.0 * half;  // mesh_block mirrors the half axis
    return across * across * depth;
}

BlockMesh mesh_block(const BlockMeshSpec& spec) {
    if (!(spec.half_width_m > 0.0) || !(spec.depth_m > 0.0) || !(spec.element_size_m > 0.0))
        throw std::invalid_argument("mesh_block: block sizes and element size must be positive");
    BlockMesh b;
    const std::vector<double> half = graded_axis(spec.half_width_m, spec.fine_half_width_m, spec.element_size_m, spec.growth);
    if (spec.quarter) {
        b.xs = half;
    } else {
        for (auto it = half.rbegin(); it != half.rend(); ++it) b.xs.push_back(-*it);
        for (std::size_t i = 1; i < half.size(); ++i) b.xs.push_back(half[i]);
    }
    b.ys = b.xs;
    for (double d : graded_axis(spec.depth_m, spec.fine_depth_m, spec.element_size_m, spec.growth)) b.zs.push_back(-d);
    std::reverse(b.zs.begin(), b.zs.end());

    const int nx = static_cast<int>(b.xs.size()), ny = static_cast<int>(b.ys.size()), nz = static_cast<int>(b.zs.size());
    auto node = [&](int i, int j, int k) { return i + nx * (j + ny * k); };
    b.mesh.nodes.reserve(static_cast<std::size_t>(nx) * ny * nz);
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                b.mesh.nodes.emplace_back(b.xs[static_cast<std::size_t>(i)], b.ys[static_cast<std::size_t>(j)],
                                          b.zs[static_cast<std::size_t>(k)]);
                if (k == nz - 1) b.top.push_back(node(i, j, k));
                if (k == 0) b.bottom.push_back(node(i, j, k));
                if (i == 0) b.x_min.push_back(node(i, j, k));
                if (i == nx - 1) b.x_max.push_back(node(i, j, k));
                if (j == 0) b.y_min.push_back(node(i, j, k));
                if (j == ny - 1) b.y_max.push_back(node(i, j, k));
            }
    for (int k = 0; k + 1 < nz; ++k)
        for (int j = 0; j + 1 < ny; ++j)
            for (int i = 0; i + 1 < nx; ++i) {
                if (k + 2 == nz) b.top_elements.push_back(static_cast<int>(b.mesh.elements.size()));
                b.mesh.elements.push_back(grid_cell(i, j, k, node));
            }
    const int j0 = spec.quarter ? 0 : ny / 2;  // the full grid is symmetric: its middle line is y = 0
    for (int i = 0; i < nx; ++i)
        if (b.xs[static_cast<std::size_t>(i)] >= 0.0) b.profile.push_back(node(i, j0, nz - 1));
    // The column whose corner is the centre (i0, j0) on the x and y >= 0 side; elements are numbered
    // i fastest, then j, then k from the bottom.
    const int i0 = spec.quarter ? 0 : nx / 2;
    for (int k = nz - 2; k >= 0; --k) b.axis_elements.push_back(i0 + (nx - 1) * (j0 + (ny - 1) * k));
    return b;
}

}  // namespace peensim
