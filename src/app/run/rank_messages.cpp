#include "app/run/rank_messages.h"

#include <chrono>
#include <thread>

#include <mpi.h>

namespace peensim {

namespace {

bool plan_sent = false;  // rank 0: the plan, or "none", went out (once per job)

}  // namespace

int rank_count() {
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    return size;
}

void pause_briefly() { std::this_thread::sleep_for(std::chrono::milliseconds(2)); }

bool message_waiting(int source, int tag) {
    int flag = 0;
    MPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
    return flag != 0;
}

void send_bytes(const std::string& bytes, int to, int tag) {
    MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD);
}

std::string receive_bytes(int from, int tag) {
    while (!message_waiting(from, tag)) pause_briefly();
    MPI_Status status;
    MPI_Probe(from, tag, MPI_COMM_WORLD, &status);
    int size = 0;
    MPI_Get_count(&status, MPI_BYTE, &size);
    std::string bytes(static_cast<std::size_t>(size), '\0');
    MPI_Recv(bytes.data(), size, MPI_BYTE, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return bytes;
}

bool receive_next(int from, int& tag, std::string& bytes) {
    int flag = 0;
    MPI_Status status;
    // Any tag: messages from one sender that all match are received in the order they were sent.
    MPI_Iprobe(from, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
    if (!flag) return false;
    tag = status.MPI_TAG;
    int size = 0;
    MPI_Get_count(&status, MPI_BYTE, &size);
    bytes.assign(static_cast<std::size_t>(size), '\0');
    MPI_Recv(bytes.data(), size, MPI_BYTE, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return true;
}

void send_int(int value, int to, int tag) { MPI_Send(&value, 1, MPI_INT, to, tag, MPI_COMM_WORLD); }

int receive_int(int from, int tag) {
    int value = 0;
    MPI_Recv(&value, 1, MPI_INT, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return value;
}

bool plan_went_out() { return plan_sent; }
void mark_plan_sent() { plan_sent = true; }

}  // namespace peensim
