// The messages between the ranks of a run's MPI job (app/run/replica_ranks.h, round_ranks.h):
// their tags, and sends and receives of bytes. Receives poll with short sleeps, so that a rank
// that waits leaves its core to the ranks that work (an oversubscribed job on a few cores still
// runs at their speed). Only in a build with Open MPI.
#pragma once

#include <string>

namespace peensim {

enum RankTag : int {
    kTagPlan = 11,    // rank 0 -> rank k: the plan's bytes (a replicas' plan without windows: none, end)
    kTagResult = 12,  // rank k -> rank 0: 'R' and its result's bytes, or 'E ' and why it failed
    kTagStop = 13,    // rank 0 -> rank k: stop at the next step (the run was interrupted or ended)
    kTagBye = 14,     // rank 0 -> rank k: its result is in; end
    kTagSlot = 15,    // rank k -> rank 0: a slot of a run until coverage it ended (round_ranks.h)
    kTagGo = 16,      // rank 0 -> rank k: the round (its decimal digits) it may run
};

int rank_count();
void pause_briefly();
// Whether a message from `source` with `tag` is waiting.
bool message_waiting(int source, int tag);
void send_bytes(const std::string& bytes, int to, int tag);
// Waits (polling) for the next message from `from` with `tag`.
std::string receive_bytes(int from, int tag);
// The next message from `from` whatever its tag, in the order they were sent, if one is waiting:
// its tag and bytes; false if none.
bool receive_next(int from, int& tag, std::string& bytes);
void send_int(int value, int to, int tag);
int receive_int(int from, int tag);

// Rank 0: whether the plan (or "none") went out to the other ranks; once per job.
bool plan_went_out();
void mark_plan_sent();

}  // namespace peensim
