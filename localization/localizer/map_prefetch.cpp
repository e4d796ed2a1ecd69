#include "localization/localizer/map_prefetch.hpp"

#include <pthread.h>

#include <utility>

#include "hal/common/thread_cpu_time.hpp"

namespace flat2d::localization {

MapPrefetch::MapPrefetch(MapWindow spare_window, std::unique_ptr<MatchMap> spare_map)
    : window_(std::move(spare_window)), map_(std::move(spare_map)), worker_([this] { Work(); }) {
  // Named so that top -H and /proc/PID/task show it beside the daemon's other threads.
  pthread_setname_np(worker_.native_handle(), "f2d-mapfill");
}

MapPrefetch::~MapPrefetch() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

void MapPrefetch::Start(maps::PriorMapReader& map, const Eigen::Vector2d& centre) {
  centre_ = centre;
  started_ = true;
  {
    std::lock_guard lock(mutex_);
    job_map_ = &map;
    running_ = true;
  }
  wake_.notify_all();
}

Status MapPrefetch::Finish() {
  std::unique_lock lock(mutex_);
  waited_ = running_;
  wake_.wait(lock, [this] { return !running_; });
  return job_status_;
}

void MapPrefetch::Take(MapWindow& window, CorrelativeMatcher& matcher) {
  std::swap(window, window_);
  map_ = matcher.ExchangeMap(std::move(map_));
  started_ = false;
}

void MapPrefetch::Work() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stopping_ || running_; });
    if (stopping_) return;
    maps::PriorMapReader& map = *job_map_;
    lock.unlock();
    // Outside the lock: the tracking thread reads only idle state until Finish.
    const double start = ThreadCpuSeconds();
    Status status = Status::Ok();
    if (const Result<bool> filled = window_.Cover(map, centre_, 0.0); !filled.ok()) {
      status = filled.error();
    } else {
      status = map_->Rebuild(window_.grid());
    }
    const double cpu_s = ThreadCpuSeconds() - start;
    lock.lock();
    job_status_ = std::move(status);
    job_cpu_s_ = cpu_s;
    running_ = false;
    wake_.notify_all();
  }
}

}  // namespace flat2d::localization
