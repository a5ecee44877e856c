#include "analysis/impact_stream.h"

#include <algorithm>

#include "common/text_excerpt.h"

namespace peensim {

ImpactStream::ImpactStream(const std::string& path, std::vector<std::string> component_names, ReaderSideWork work,
                           bool every_component_named)
    : reader_(path),
      names_(std::move(component_names)),
      work_(std::move(work)),
      every_component_named_(every_component_named),
      blocks_(kBlocks) {
    for (Block& b : blocks_) b.rows.resize(kRowsPerBlock);
    thread_ = std::thread([this] { read_all(); });
}

ImpactStream::~ImpactStream() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    changed_.notify_all();
    thread_.join();
}

void ImpactStream::read_all() {
    Block* block = nullptr;
    try {
        for (;;) {
            {
                // The block the reader fills next must not be one the consumer may still read:
                // at most kBlocks - 1 filled and not yet released.
                std::unique_lock lock(mutex_);
                changed_.wait(lock, [&] { return stop_ || filled_ + 1 < taken_ + kBlocks; });
                if (stop_) return;
                block = &blocks_[filled_ % kBlocks];
            }
            block->size = 0;
            bool more = true;
            while (block->size < kRowsPerBlock && (more = reader_.next(block->rows[block->size].row))) {
                IndexedImpact& r = block->rows[block->size];
                const auto name = std::find(names_.begin(), names_.end(), r.row.component);
                r.component = name == names_.end() ? -1 : static_cast<int>(name - names_.begin());
                if (r.component < 0 && every_component_named_) refuse_component(r.row.component);
                r.row.component = {};
                if (work_ && r.component >= 0) work_(r.row, r.component);
                ++block->size;
            }
            {
                std::lock_guard lock(mutex_);
                if (block->size > 0) ++filled_;
                block = nullptr;
                if (!more) done_ = true;
            }
            changed_.notify_all();
            if (!more) return;
        }
    } catch (...) {
        {
            // The rows read before the bad one are delivered first, then the error.
            std::lock_guard lock(mutex_);
            if (block != nullptr && block->size > 0) ++filled_;
            error_ = std::current_exception();
            done_ = true;
        }
        changed_.notify_all();
    }
}

void ImpactStream::refuse_component(std::string_view name) const {
    std::string names;
    for (const std::string& n : names_) names += (names.empty() ? "'" : ", '") + n + "'";
    reader_.refuse_row("component", "expected a component the run logs (" + names + "), got " + text_excerpt(name));
}

std::span<const IndexedImpact> ImpactStream::next_block() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return taken_ < filled_ || done_; });
    if (taken_ < filled_) {
        const Block& block = blocks_[taken_ % kBlocks];
        ++taken_;  // the previous block is released: the reader may refill it
        lock.unlock();
        changed_.notify_all();
        return {block.rows.data(), block.size};
    }
    if (error_) std::rethrow_exception(error_);
    return {};
}

}  // namespace peensim
