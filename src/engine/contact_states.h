// What surface laws remember per contact while it lasts (SurfaceLaw::state_per_contact()): a
// contact is a shot in sustained contact with a component (resting, rolling, sliding on it). It
// starts with zeros the first time a scheme resolves it, lasts while every resolution of that shot
// finds it again (each time step of time stepping, each substep of the event scheme's sustained
// contact), and ends at the first that does not, or when the shot flies off, is lost or collected.
// Impacts in the rigid schemes are instantaneous: each is a contact of its own, with zeros.
// Lives in the simulation state and its checkpoint; empty unless a law asks for it.
#pragma once

#include <cstdint>
#include <iterator>
#include <map>
#include <span>
#include <utility>
#include <vector>

namespace peensim {

class ContactStates {
public:
    struct Entry {
        std::uint64_t seen = 0;      // the resolution that last found this contact
        std::vector<double> values;  // the law's state_per_contact() doubles
    };
    using Key = std::pair<int, int>;  // (shot, component)

    // A new resolution (a step, a substep): its stamp, for touch() and end_unseen().
    std::uint64_t begin_resolution() { return ++resolutions_; }

    // The state of shot's contact with component c (n doubles, zeros if it is new), found in
    // resolution `stamp`.
    std::span<double> touch(int shot, int component, std::size_t n, std::uint64_t stamp) {
        Entry& e = entries_[{shot, component}];
        if (e.values.size() != n) e.values.assign(n, 0.0);
        e.seen = stamp;
        return e.values;
    }
    // Ends every contact not found in resolution `stamp` (shot < 0: of every shot).
    void end_unseen(std::uint64_t stamp, int shot = -1) {
        auto it = shot < 0 ? entries_.begin() : entries_.lower_bound({shot, -1});
        while (it != entries_.end() && (shot < 0 || it->first.first == shot))
            it = it->second.seen == stamp ? std::next(it) : entries_.erase(it);
    }
    // Ends every contact of a shot (it flew off, was lost or collected).
    void end_all(int shot) {
        auto it = entries_.lower_bound({shot, -1});
        while (it != entries_.end() && it->first.first == shot) it = entries_.erase(it);
    }

    // In key order (the checkpoint's order).
    const std::map<Key, Entry>& entries() const { return entries_; }
    std::uint64_t resolutions() const { return resolutions_; }
    // A checkpoint's entries back.
    void restore(std::uint64_t resolutions, std::map<Key, Entry> entries) {
        resolutions_ = resolutions;
        entries_ = std::move(entries);
    }

private:
    std::map<Key, Entry> entries_;
    std::uint64_t resolutions_ = 0;
};

}  // namespace peensim
