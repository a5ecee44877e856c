// A replica's result as bytes and back (app/run/replica_runs.h, round_runs.h): how a replica run on
// another MPI rank (app/run/replica_ranks.h, round_ranks.h) hands rank 0 what the run's summary
// merges from it. Only those fields travel: the window, the counts at its start and end, the steps,
// the speeds, the lost shot and the health counters, the wall time.
#pragma once

#include <string>
#include <string_view>

#include "app/run/replica_plan.h"
#include "app/run/replica_rounds.h"
#include "app/run/replica_runs.h"
#include "app/run/round_runs.h"

namespace peensim {

std::string encode_replica_result(const ReplicaResult& r);
// Throws std::runtime_error on bytes that are not encode_replica_result's.
ReplicaResult decode_replica_result(std::string_view bytes);

// The plan as bytes and back (rank 0 hands it to the other ranks); an empty plan: none (the run
// goes on as one replica, or stopped before it had one).
std::string encode_replica_plan(const ReplicaPlan& plan);
ReplicaPlan decode_replica_plan(std::string_view bytes);

// A run until coverage over ranks (app/run/round_ranks.h): its plan, each slot a replica ran and
// each replica's whole run, as bytes and back (the decoders throw std::runtime_error on other
// bytes). is_round_plan: whether a plan's bytes are a rounds' plan (else encode_replica_plan's).
std::string encode_round_plan(const RoundPlan& plan);
bool is_round_plan(std::string_view bytes);
RoundPlan decode_round_plan(std::string_view bytes);
std::string encode_slot_result(const SlotResult& slot);
SlotResult decode_slot_result(std::string_view bytes);
std::string encode_round_replica_result(const RoundReplicaResult& result);
RoundReplicaResult decode_round_replica_result(std::string_view bytes);

}  // namespace peensim
