// Whole-mesh passes that only read (the validity check, the lookup of the
// input triangles among the mesh's faces, Table II) cut into contiguous chunks, one
// thread each (CBR_PARAM_THREADS). Each chunk fills its own result and the
// caller merges them in chunk order, so the answer is the one pass's, bit
// for bit, whatever the number of threads.
#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <system_error>
#include <thread>
#include <vector>

namespace cbr::mesh {

// Fewer items than this in a chunk are not worth a thread (starting and
// joining one costs tens of microseconds; a chunk of this many tetrahedra
// takes about a millisecond to check).
constexpr std::size_t kMinChunk = std::size_t{1} << 14;

// How many chunks a pass over `count` items takes with `threads` threads:
// at least 1, at most `threads`, none smaller than kMinChunk (but one).
inline std::size_t chunk_count(std::size_t count, int threads) {
    const std::size_t most = threads > 1 ? static_cast<std::size_t>(threads) : 1;
    return std::max<std::size_t>(1, std::min(most, count / kMinChunk));
}

// Chunk k of `chunks` over [0, count): [begin, end).
inline std::size_t chunk_begin(std::size_t count, std::size_t chunks, std::size_t k) {
    return static_cast<std::size_t>(static_cast<unsigned long long>(count) * k / chunks);
}

// Runs work(k, begin, end) for each of the `chunks` chunks of [0, count):
// chunk 0 on the calling thread, the others on threads of their own (or on
// the calling thread, after chunk 0, when a thread cannot be started).
// Returns when every chunk is done; an exception of a chunk is rethrown
// then (the lowest chunk's first).
template <class Work>
void run_chunks(std::size_t count, std::size_t chunks, Work work) {
    std::vector<std::exception_ptr> failed(chunks);
    const auto run = [&](std::size_t k) {
        try {
            work(k, chunk_begin(count, chunks, k), chunk_begin(count, chunks, k + 1));
        } catch (...) {
            failed[k] = std::current_exception();
        }
    };
    std::vector<std::thread> started;
    std::vector<std::size_t> inline_chunks;
    started.reserve(chunks);  // no reallocation once a thread runs
    inline_chunks.reserve(chunks);
    for (std::size_t k = 1; k < chunks; ++k) {
        try {
            started.emplace_back(run, k);
        } catch (const std::system_error&) {
            inline_chunks.push_back(k);
        }
    }
    run(0);
    for (std::size_t k : inline_chunks) run(k);
    for (std::thread& t : started) t.join();
    for (const std::exception_ptr& e : failed)
        if (e) std::rethrow_exception(e);
}

}  // namespace cbr::mesh
