#pragma once
// One thread beside the caller's that runs one task at a time. The renderer marches an object's geodesic
// patch on it while its own thread draws what no dent reaches: on llvmpipe that thread also runs the
// vertex stage of that draw, so the march no longer adds to the frame (docs/design.md).
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace palpate::gl {

class SideThread {
 public:
  SideThread();
  // Stops the thread once the task in hand is done.
  ~SideThread();
  SideThread(const SideThread&) = delete;
  SideThread& operator=(const SideThread&) = delete;

  // Hands `task` to the thread, after the one before it is done. `task` must not throw.
  void start(std::function<void()> task);
  // Returns once the task handed last is done: what it wrote may then be read.
  void wait();

 private:
  void run();

  std::mutex mutex_;
  std::condition_variable changed_;
  std::function<void()> task_;
  bool busy_ = false, stopping_ = false;
  std::thread thread_;  // last: started once the members it reads are made
};

}  // namespace palpate::gl
