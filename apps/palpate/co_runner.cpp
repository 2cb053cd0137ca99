#include "co_runner.hpp"

#include <epoxy/gl.h>
#include <pthread.h>
#include <sched.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>
#include <vector>

#include "palpate/core/error.hpp"
#include "palpate/core/scene_file.hpp"
#include "palpate/gl/framebuffer.hpp"
#include "palpate/gl/headless_context.hpp"
#include "palpate/gl/renderer.hpp"

namespace palpate::cli {
namespace {

void pin_to(int core) noexcept {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(core, &set);
  pthread_setaffinity_np(pthread_self(), sizeof set, &set);  // refused: left where it is
}

// Two buffers of 64 MiB each, copied back and forth: larger than any last-level cache here.
void stream_memory(const std::atomic<bool>& stop, std::atomic<bool>& started, std::atomic<long long>& work) {
  constexpr std::size_t bytes = 64u << 20;
  std::vector<unsigned char> a(bytes, 1), b(bytes, 2);
  started.store(true);
  while (!stop.load(std::memory_order_relaxed)) {
    std::memcpy(b.data(), a.data(), bytes);
    std::memcpy(a.data(), b.data(), bytes);
    work.fetch_add(128, std::memory_order_relaxed);
  }
}

// The Table I scene (phantom brain in skin) drawn with a dent that circles on the skin, 1280x1024.
void render_frames(const std::atomic<bool>& stop, std::atomic<bool>& started, std::atomic<long long>& work,
                   std::string& error) {
  try {
    gl::HeadlessContext context;
    const gl::Framebuffer target({.width = 1280, .height = 1024});
    gl::Renderer renderer;
    const Scene scene = phantom_scene();
    renderer.upload(scene);
    const glm::mat4 view = glm::lookAt(glm::vec3(0, -300, 60), glm::vec3(0, 0, 20), glm::vec3(0, 0, 1));
    const glm::mat4 projection = glm::perspective(glm::radians(40.0f), 1.25f, 10.0f, 2000.0f);
    for (long long frame = 0; !stop.load(std::memory_order_relaxed); ++frame) {
      const float angle = 0.05f * float(frame);
      const gl::ObjectDent dent{1, Dent{glm::vec3(40.0f * std::cos(angle), -95.0f, 40.0f * std::sin(angle)),
                                        4.0f, skin_material.sigma_mm}};
      target.bind();
      renderer.draw(view, projection, {&dent, 1});
      glFinish();
      work.fetch_add(1, std::memory_order_relaxed);
      started.store(true);
    }
  } catch (const std::exception& e) {
    error = e.what();
    started.store(true);
  }
}

}  // namespace

const char* load_name(Load load) noexcept {
  switch (load) {
    case Load::memory:
      return "memory";
    case Load::render:
      return "render";
    case Load::idle:
      break;
  }
  return "idle";
}

CoRunner::CoRunner(Load load, int core) {
  if (load == Load::idle) return;
  thread_ = std::thread([this, load, core] {
    pin_to(core);  // before the renderer starts its own threads: they inherit the core
    if (load == Load::memory) {
      stream_memory(stop_, started_, work_);
    } else {
      render_frames(stop_, started_, work_, error_);
    }
  });
  while (!started_.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  if (!error_.empty()) {
    thread_.join();
    throw Error("bench haptics: the render co-runner could not start: " + error_);
  }
}

CoRunner::~CoRunner() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

PinnedToCore::PinnedToCore(int core) noexcept {
  static_assert(sizeof(cpu_set_t) <= sizeof previous_);
  cpu_set_t previous;
  if (pthread_getaffinity_np(pthread_self(), sizeof previous, &previous) != 0) return;
  std::memcpy(previous_, &previous, sizeof previous);
  restored_needed_ = true;
  pin_to(core);
}

PinnedToCore::~PinnedToCore() {
  if (!restored_needed_) return;
  cpu_set_t previous;
  std::memcpy(&previous, previous_, sizeof previous);
  pthread_setaffinity_np(pthread_self(), sizeof previous, &previous);
}

}  // namespace palpate::cli
