// SampleClasses as bytes and back: every member in order, each vector with its length, so that a
// set read back answers every query as the one written (the sweep's cache of the coverage geometry).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "analysis/sample_classes.h"

namespace peensim {

void SampleClasses::write_bytes(ByteWriter& out) const {
    out.put<std::uint64_t>(classes_.size());
    for (const SampleClass& c : classes_) {
        out.put<std::uint8_t>(c.reachable ? 1 : 0);
        out.put<std::uint8_t>(c.excluded ? 1 : 0);
        out.put_vector(c.regions);
        out.put(c.area_m2);
    }
    out.put_vector(triangle_class_);
    out.put_vector(mixed_start_);
    out.put_vector(first_sample_);
    // The mixed triangles' samples (11 M on the shipped gear) as runs of one class: a row of samples
    // changes class where it crosses a reach or region boundary, once or twice.
    std::vector<std::uint16_t> run_class;
    std::vector<std::uint32_t> run_length;
    for (std::size_t i = 0; i < sample_class_.size(); ++i) {
        if (run_class.empty() || run_class.back() != sample_class_[i] || run_length.back() == UINT32_MAX) {
            run_class.push_back(sample_class_[i]);
            run_length.push_back(0);
        }
        ++run_length.back();
    }
    out.put<std::uint64_t>(sample_class_.size());
    out.put_vector(run_class);
    out.put_vector(run_length);
    out.put_vector(reachable_samples_);
    out.put_vector(peened_samples_);
    out.put_vector(region_peened_m2_);
    out.put_vector(region_counted_m2_);
    out.put_vector(region_unreachable_m2_);
    out.put_vector(std::vector<std::uint8_t>(region_excluded_.begin(), region_excluded_.end()));
    out.put<std::uint64_t>(region_classes_.size());
    for (const std::vector<std::uint16_t>& r : region_classes_) out.put_vector(r);
    out.put(peened_area_m2_);
    out.put(reachable_area_m2_);
    out.put(reach_tests_);
    out.put(sample_tests_);
}

SampleClasses SampleClasses::read_bytes(ByteReader& in, std::size_t triangles, std::size_t regions) {
    SampleClasses s;
    const auto classes = in.get<std::uint64_t>();
    if (classes > kMixed) in.fail("more sample classes than a class index holds");
    s.classes_.resize(classes);
    for (SampleClass& c : s.classes_) {
        c.reachable = in.get<std::uint8_t>() != 0;
        c.excluded = in.get<std::uint8_t>() != 0;
        c.regions = in.get_vector<std::uint32_t>();
        c.area_m2 = in.get<double>();
        for (std::uint32_t r : c.regions)
            if (r >= regions) in.fail("a class in a region the part does not have");
    }
    s.triangle_class_ = in.get_vector<std::uint16_t>();
    s.mixed_start_ = in.get_vector<std::int64_t>();
    s.first_sample_ = in.get_vector<std::int64_t>();
    const auto samples = in.get<std::uint64_t>();
    const std::vector<std::uint16_t> run_class = in.get_vector<std::uint16_t>();
    const std::vector<std::uint32_t> run_length = in.get_vector<std::uint32_t>();
    std::uint64_t total = 0;
    for (std::uint32_t n : run_length) total += n;
    if (run_class.size() != run_length.size() || total != samples) in.fail("sample runs that do not add up");
    s.sample_class_.reserve(samples);
    for (std::size_t r = 0; r < run_class.size(); ++r) s.sample_class_.insert(s.sample_class_.end(), run_length[r], run_class[r]);
    s.reachable_samples_ = in.get_vector<std::int64_t>();
    s.peened_samples_ = in.get_vector<std::int64_t>();
    s.region_peened_m2_ = in.get_vector<double>();
    s.region_counted_m2_ = in.get_vector<double>();
    s.region_unreachable_m2_ = in.get_vector<double>();
    const std::vector<std::uint8_t> excluded = in.get_vector<std::uint8_t>();
    s.region_excluded_.assign(excluded.begin(), excluded.end());
    if (in.get<std::uint64_t>() != regions) in.fail("not one entry per region of the part");
    s.region_classes_.resize(regions);
    for (std::vector<std::uint16_t>& r : s.region_classes_) r = in.get_vector<std::uint16_t>();
    s.peened_area_m2_ = in.get<double>();
    s.reachable_area_m2_ = in.get<double>();
    s.reach_tests_ = in.get<std::uint64_t>();
    s.sample_tests_ = in.get<std::uint64_t>();
    // The sizes every query relies on, and every class index in range (a query indexes with them).
    const auto per_triangle = [&](std::size_t n) { return n == triangles; };
    const auto per_region = [&](std::size_t n) { return n == regions; };
    if (!per_triangle(s.triangle_class_.size()) || !per_triangle(s.mixed_start_.size()) || !per_triangle(s.first_sample_.size()) ||
        !per_triangle(s.reachable_samples_.size()) || !per_triangle(s.peened_samples_.size()))
        in.fail("not one entry per triangle of the part");
    if (!per_region(s.region_peened_m2_.size()) || !per_region(s.region_counted_m2_.size()) ||
        !per_region(s.region_unreachable_m2_.size()) || !per_region(s.region_excluded_.size()) || !per_region(s.region_classes_.size()))
        in.fail("not one entry per region of the part");
    const auto in_range = [&](std::uint16_t k) { return k < s.classes_.size(); };
    for (std::uint16_t k : s.triangle_class_)
        if (k != kMixed && !in_range(k)) in.fail("a triangle of no class");
    for (std::uint16_t k : s.sample_class_)
        if (!in_range(k)) in.fail("a sample of no class");
    for (const std::vector<std::uint16_t>& r : s.region_classes_)
        for (std::uint16_t k : r)
            if (!in_range(k)) in.fail("a region of no class");
    for (std::size_t t = 0; t < triangles; ++t)
        if (s.triangle_class_[t] == kMixed &&
            !(s.mixed_start_[t] >= 0 && static_cast<std::uint64_t>(s.mixed_start_[t]) <= s.sample_class_.size()))
            in.fail("a mixed triangle's samples out of range");
    return s;
}

}  // namespace peensim
