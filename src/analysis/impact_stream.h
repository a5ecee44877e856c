// Reads an impact log on a second thread and hands the rows over in blocks, so that parsing the
// text (and whatever per-row work the caller gives the reader thread, e.g. writing the impacts'
// ParaView file) overlaps with the analysis of the previous block. Memory is a few fixed blocks,
// whatever the size of the log; blocks are recycled, nothing is allocated per row.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "analysis/impact_log_reader.h"

namespace peensim {

// One row of the log with its component as an index into the names the stream was given
// (-1: a component not among them). row.component is empty: the text it pointed to is gone.
struct IndexedImpact {
    ImpactRow row;
    int component = -1;
};

class ImpactStream {
public:
    // Called on the reader thread for every row of a named component, in log order.
    using ReaderSideWork = std::function<void(const ImpactRow&, int component)>;

    // Opens the log (throws like ImpactLogReader, on the calling thread) and starts reading.
    // `every_component_named`: the names are every component the run logged, so a row of another
    // is damage (an InputError at its line, from next_block()), not a row to skip.
    ImpactStream(const std::string& path, std::vector<std::string> component_names, ReaderSideWork work = {},
                 bool every_component_named = false);
    ~ImpactStream();  // stops the reader thread (also when the consumer gave up early)
    ImpactStream(const ImpactStream&) = delete;
    ImpactStream& operator=(const ImpactStream&) = delete;

    // The next rows, in log order; empty at the end of the log. Valid until the next call.
    // Rethrows on the calling thread what the reader thread threw (a bad line, a failed write).
    std::span<const IndexedImpact> next_block();

    bool truncated() const { return reader_.truncated(); }  // meaningful once next_block() is empty
    std::uint64_t truncated_line() const { return reader_.truncated_line(); }
    std::uint64_t rows() const { return reader_.rows(); }

private:
    static constexpr std::size_t kBlocks = 4;
    static constexpr std::size_t kRowsPerBlock = 8192;

    struct Block {
        std::vector<IndexedImpact> rows;
        std::size_t size = 0;
    };

    void read_all();
    [[noreturn]] void refuse_component(std::string_view name) const;

    ImpactLogReader reader_;
    std::vector<std::string> names_;
    ReaderSideWork work_;
    bool every_component_named_ = false;

    // Ring of blocks: the reader fills blocks_[filled_ % kBlocks], the consumer reads
    // blocks_[taken_ % kBlocks]; the consumer holds block taken_ - 1 until its next call.
    std::vector<Block> blocks_;
    std::uint64_t filled_ = 0, taken_ = 0;
    bool done_ = false, stop_ = false;
    std::exception_ptr error_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::thread thread_;
};

}  // namespace peensim
