// Work cut into a fixed number of chunks, run on every core: the analysis's passes over tens of
// millions of coverage samples. The chunks, not the threads, decide what is summed together, so a
// caller that keeps one result per chunk and merges them in chunk order gets the same bytes on any
// number of cores.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace peensim {

// The threads for_each_chunk uses by default: set_analysis_threads's, else one per core.
inline std::atomic<unsigned>& analysis_threads_wanted() {
    static std::atomic<unsigned> wanted{0};
    return wanted;
}
inline void set_analysis_threads(unsigned threads) { analysis_threads_wanted() = threads; }  // 0: one per core
// Work done ahead beside a run (the analysis's geometry while it steps) takes only the cores the
// run leaves: its thread points this at its own count, and its calls use that many threads (0: as
// above). The count may grow while a call runs (once the run is done and waits for that work), and
// the call then takes on more threads at its next chunk.
inline thread_local const std::atomic<unsigned>* chunk_threads_here = nullptr;
inline unsigned analysis_threads() {
    if (chunk_threads_here != nullptr)
        if (const unsigned here = chunk_threads_here->load(std::memory_order_relaxed); here > 0) return here;
    const unsigned wanted = analysis_threads_wanted();
    return wanted > 0 ? wanted : std::max(1u, std::thread::hardware_concurrency());
}

// Work done ahead on a thread of its own (the analysis's geometry while a run steps) can be
// abandoned: that thread points chunk_cancel at a flag, and once it is set every for_each_chunk
// it calls starts no more chunks and throws ChunksCancelled.
struct ChunksCancelled : std::exception {
    const char* what() const noexcept override { return "cancelled"; }
};
inline thread_local const std::atomic<bool>* chunk_cancel = nullptr;
inline void throw_if_chunks_cancelled() {
    if (chunk_cancel != nullptr && chunk_cancel->load(std::memory_order_relaxed)) throw ChunksCancelled();
}

// Calls f(chunk) once for every chunk in 0 .. chunks - 1, on up to `threads` threads (this one
// among them), each chunk on one thread, in no particular order; returns when all are done and
// rethrows the first exception one threw (the chunks not yet started are skipped). threads 0:
// analysis_threads(), asked again after each chunk this thread runs, so that a call begun on the
// cores a run left idle takes on the others when the run gives them up.
template <class F>
void for_each_chunk(std::size_t chunks, F&& f, unsigned threads = 0) {
    const std::atomic<bool>* const cancel = chunk_cancel;  // the caller's: the helpers have their own
    std::atomic<std::size_t> next{0};
    std::exception_ptr failure;
    std::mutex failure_mutex;
    const auto run = [&](std::size_t c) {
        try {
            if (cancel != nullptr && cancel->load(std::memory_order_relaxed)) throw ChunksCancelled();
            f(c);
        } catch (...) {
            const std::lock_guard<std::mutex> lock(failure_mutex);
            if (!failure) failure = std::current_exception();
            next = chunks;  // start no more
        }
    };
    const auto work = [&] {
        for (std::size_t c = next++; c < chunks; c = next++) run(c);
    };
    std::vector<std::thread> helpers;
    const auto hire = [&] {
        const std::size_t wanted = std::min<std::size_t>(threads > 0 ? threads : analysis_threads(), chunks);
        while (helpers.size() + 1 < wanted && next < chunks) helpers.emplace_back(work);
    };
    hire();
    for (std::size_t c = next++; c < chunks; c = next++) {
        run(c);
        if (threads == 0) hire();
    }
    for (std::thread& h : helpers) h.join();
    if (failure) std::rethrow_exception(failure);
}

// [begin, end) of chunk c of n items cut into `chunks` nearly equal parts.
inline std::pair<std::size_t, std::size_t> chunk_range(std::size_t n, std::size_t chunks, std::size_t c) {
    return {n * c / chunks, n * (c + 1) / chunks};
}

}  // namespace peensim
