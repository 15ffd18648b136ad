#pragma once
// FifoWriter: for tests of loaders that must not open a FIFO. Were a loader to open it anyway, the
// writer lets it read the FIFO's end, so that the test fails on its message instead of hanging.

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>

namespace spatter::test {

// Opens `path`, a FIFO, for writing whenever a reader has opened it, and closes it at once: a loader
// that opens the FIFO then reads its end instead of waiting forever.
class FifoWriter {
public:
    explicit FifoWriter(const std::string& path)
        : thread_([this, path] {
              while (!stop_) {
                  if (const int fd = open(path.c_str(), O_WRONLY | O_NONBLOCK); fd >= 0) close(fd);
                  std::this_thread::sleep_for(std::chrono::milliseconds(1));
              }
          }) {}
    ~FifoWriter() {
        stop_ = true;
        thread_.join();
    }

private:
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

} // namespace spatter::test
