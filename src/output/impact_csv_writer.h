// Streams the impacts of a run to <dir>/impacts.csv, one row per ImpactRecord, without
// holding them in memory. Rows go to <dir>/impacts.csv.partial while the run goes; finish()
// renames it to impacts.csv, so a complete impacts.csv exists only for a finished run and a
// killed run leaves just the .partial, which resume() continues from a checkpoint.
//
// Numbers are written with std::to_chars in their shortest round-trip form: reading a field
// back with strtod/from_chars gives the identical double, and the same run gives the same
// bytes. Rows are formatted into a fixed buffer owned by the writer (no allocation per row)
// and handed to write(2) when it is full.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/impact_record.h"

namespace peensim {

// The first line of impacts.csv (without its newline). Units: s, m, m/s; the point and the
// velocities are in the component's own frame; vn/vt are normal/tangential speeds (>= 0).
inline constexpr std::string_view kImpactCsvHeader =
    "time_s,shot,component,triangle,x_m,y_m,z_m,vx_in_mps,vy_in_mps,vz_in_mps,vn_in_mps,"
    "vt_in_mps,vx_out_mps,vy_out_mps,vz_out_mps,vn_out_mps";
// A run of a shot mix (several sizes) adds a last column, the shot's diameter; a run of one size
// writes none (its rows are those of every earlier version).
inline constexpr std::string_view kImpactCsvDiameterColumn = "shot_diameter_m";
// The header line a run writes (without its newline).
inline std::string impact_csv_header(bool shot_diameter) {
    return std::string(kImpactCsvHeader) + (shot_diameter ? "," + std::string(kImpactCsvDiameterColumn) : std::string());
}
inline constexpr std::string_view kImpactCsvFileName = "impacts.csv";
inline constexpr std::string_view kImpactCsvPartialFileName = "impacts.csv.partial";

// Bytes formatted before the buffer goes to the file. Large enough that write(2) calls are
// rare, small enough not to matter next to the model.
inline constexpr std::size_t kImpactCsvBufferBytes = std::size_t{1} << 20;

class ImpactCsvWriter {
public:
    // Starts a new <dir>/impacts.csv.partial (truncating one left by an earlier run) and
    // writes the header. A stale <dir>/impacts.csv is removed so it cannot be mistaken for
    // this run's output. `component_names[i]` is written for ImpactRecord::component == i.
    // shot_diameter: write the shot_diameter_m column (a run of a shot mix).
    // Throws std::runtime_error (path + errno text) if the file cannot be created.
    ImpactCsvWriter(std::string dir, std::vector<std::string> component_names, bool shot_diameter = false);

    // Continues a killed run from a checkpoint that recorded bytes_written() == bytes and
    // rows_written() == rows after flush_durable(). The .partial is truncated to exactly
    // `bytes` (dropping rows written after the checkpoint) and appended to. A run that failed
    // after finish() (impacts.csv but no .partial) is continued from its impacts.csv. Throws
    // std::runtime_error if the .partial is missing, shorter than `bytes`, does not start
    // with the header, or `bytes` does not fall at the end of a row.
    static ImpactCsvWriter resume(std::string dir, std::vector<std::string> component_names, std::uint64_t bytes, std::uint64_t rows,
                                  bool shot_diameter = false);

    ImpactCsvWriter(ImpactCsvWriter&& other) noexcept;
    ImpactCsvWriter& operator=(ImpactCsvWriter&& other) noexcept;
    ImpactCsvWriter(const ImpactCsvWriter&) = delete;
    ImpactCsvWriter& operator=(const ImpactCsvWriter&) = delete;

    // Without finish(): hands buffered rows to the .partial (best effort, no fsync) and
    // leaves it there; impacts.csv is not created.
    ~ImpactCsvWriter();

    // Appends one row. Throws std::out_of_range for a component index without a name,
    // std::logic_error after finish(), std::runtime_error when the file write fails.
    void write(const ImpactRecord& impact);
    void write(std::span<const ImpactRecord> impacts);

    // Flushes the buffer and fsyncs the file (and, the first time, its directory), so that
    // bytes_written() bytes are on disk: call it before recording a checkpoint.
    void flush_durable();

    // Flushes, fsyncs, closes and renames the .partial to impacts.csv (durably).
    void finish();

    // Bytes in the file including the header and rows still in the buffer; equal to the
    // file's length right after flush_durable().
    std::uint64_t bytes_written() const { return bytes_written_; }
    // Impact rows (not counting the header).
    std::uint64_t rows_written() const { return rows_written_; }
    bool finished() const { return fd_ < 0; }

    const std::string& partial_path() const { return partial_path_; }
    const std::string& final_path() const { return final_path_; }

private:
    struct AdoptOpenFile {};
    ImpactCsvWriter(AdoptOpenFile, std::string dir, std::vector<std::string> component_names, bool shot_diameter, int fd,
                    std::uint64_t bytes, std::uint64_t rows);

    void flush_buffer();
    void close_quietly() noexcept;

    std::string dir_;
    std::string partial_path_;
    std::string final_path_;
    std::vector<std::string> csv_names_;  // component names, CSV-quoted where needed
    bool shot_diameter_ = false;          // rows end with the shot's diameter
    std::size_t max_row_bytes_ = 0;       // bound on one formatted row
    std::size_t capacity_ = 0;            // bytes in buffer_
    std::unique_ptr<char[]> buffer_;
    std::size_t used_ = 0;  // bytes of buffer_ not yet written to the file
    int fd_ = -1;           // -1 once finished (or moved from)
    bool directory_synced_ = false;
    std::uint64_t bytes_written_ = 0;
    std::uint64_t rows_written_ = 0;
};

}  // namespace peensim
