// The event queue of the event-driven scheme: one entry per shot (its earliest pending event),
// an indexed binary min-heap on the event time. Re-predicting a shot moves its one entry up or
// down instead of pushing another, so the heap never holds stale events (the prototype's heap of
// every prediction was 27 % of its run time) and its size is the shot count. Ties are broken by
// shot index, so the order of events, and a run, is deterministic. Allocates only in reset().
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

namespace peensim {

class EventQueue {
public:
    // n entries (shots 0..n-1), every key +infinity.
    void reset(std::size_t n) {
        heap_.resize(n);
        slot_.resize(n);
        key_.assign(n, std::numeric_limits<double>::infinity());
        for (std::size_t i = 0; i < n; ++i) heap_[i] = static_cast<int>(i), slot_[i] = static_cast<int>(i);
    }
    // Entries for shots size()..n-1 (key +infinity) added, the others kept: they go to the heap's
    // end, where a key of +infinity and an index above every other keep the heap in order.
    void grow(std::size_t n) {
        for (std::size_t i = heap_.size(); i < n; ++i) {
            heap_.push_back(static_cast<int>(i));
            slot_.push_back(static_cast<int>(i));
            key_.push_back(std::numeric_limits<double>::infinity());
        }
    }
    std::size_t size() const { return heap_.size(); }
    bool empty() const { return heap_.empty(); }

    int top() const { return heap_.front(); }  // the shot with the earliest event
    // +infinity when there are no entries (a run with no shot yet).
    double top_time() const {
        return heap_.empty() ? std::numeric_limits<double>::infinity() : key_[static_cast<std::size_t>(heap_.front())];
    }
    double time_of(int shot) const { return key_[static_cast<std::size_t>(shot)]; }

    // Sets a shot's event time (s; +infinity: none) and restores the heap order.
    void set(int shot, double t) {
        const auto s = static_cast<std::size_t>(shot);
        const double old = key_[s];
        key_[s] = t;
        const auto at = static_cast<std::size_t>(slot_[s]);
        if (before(t, shot, old, shot))
            up(at);
        else
            down(at);
    }

private:
    static bool before(double ta, int a, double tb, int b) { return ta < tb || (ta == tb && a < b); }
    bool less(std::size_t i, std::size_t j) const {
        const int a = heap_[i], b = heap_[j];
        return before(key_[static_cast<std::size_t>(a)], a, key_[static_cast<std::size_t>(b)], b);
    }
    void swap_at(std::size_t i, std::size_t j) {
        std::swap(heap_[i], heap_[j]);
        slot_[static_cast<std::size_t>(heap_[i])] = static_cast<int>(i);
        slot_[static_cast<std::size_t>(heap_[j])] = static_cast<int>(j);
    }
    void up(std::size_t i) {
        while (i > 0) {
            const std::size_t parent = (i - 1) / 2;
            if (!less(i, parent)) break;
            swap_at(i, parent);
            i = parent;
        }
    }
    void down(std::size_t i) {
        const std::size_t n = heap_.size();
        for (;;) {
            const std::size_t l = 2 * i + 1, r = l + 1;
            std::size_t m = i;
            if (l < n && less(l, m)) m = l;
            if (r < n && less(r, m)) m = r;
            if (m == i) break;
            swap_at(i, m);
            i = m;
        }
    }

    std::vector<int> heap_;    // shots in heap order
    std::vector<int> slot_;    // per shot: its position in heap_
    std::vector<double> key_;  // per shot: event time, s
};

}  // namespace peensim
