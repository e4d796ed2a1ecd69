// The next map window, prepared on a worker thread while the current one is matched, so
// that a window move costs the tracking thread an exchange of buffers instead of a fill and
// a score-table rebuild (40-60 ms for a 100 m window: over the p99 budget of a revolution).
//
// The localizer starts a job once the vehicle is halfway to the recentre distance, centred
// where it will then be if it keeps its direction; when the move falls due, it waits for the
// job if it is still running and takes the prepared window if the vehicle is near its centre
// (else it fills synchronously, as without prefetch). The decisions depend only on the poses,
// never on the worker's timing, so a replay gives the same matches every time. While
// a job runs the map reader is the worker's: the localizer touches it only after Finish().
// Everything is sized at construction; a job allocates nothing.
#pragma once

#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>

#include <Eigen/Core>

#include "hal/common/error.hpp"
#include "localization/localizer/map_window.hpp"
#include "localization/matching/correlative_matcher.hpp"
#include "maps/prior_map/prior_map_reader.hpp"

namespace flat2d::localization {

class MapPrefetch {
 public:
  // The spare window and match map (sized like the matched ones) and the worker thread.
  MapPrefetch(MapWindow spare_window, std::unique_ptr<MatchMap> spare_map);
  ~MapPrefetch();  // waits for a running job
  MapPrefetch(const MapPrefetch&) = delete;
  MapPrefetch& operator=(const MapPrefetch&) = delete;

  // Starts preparing the spare around `centre`; `map` belongs to the worker until Finish.
  // Only when idle().
  void Start(maps::PriorMapReader& map, const Eigen::Vector2d& centre);
  // No job started since the last Take or Discard.
  bool idle() const { return !started_; }
  // Waits for the started job; its status (ok: the spare holds the window around centre()).
  // The wait is at most the rest of a fill the caller would otherwise do itself.
  Status Finish();
  // Whether the last Finish found the job still running (the worker fell behind).
  bool last_finish_waited() const { return waited_; }
  const Eigen::Vector2d& centre() const { return centre_; }
  // After a successful Finish: exchanges the prepared window and map with the matched ones.
  void Take(MapWindow& window, CorrelativeMatcher& matcher);
  // After Finish: forgets the job's result.
  void Discard() { started_ = false; }
  // The worker's CPU time for the last finished job.
  double last_job_cpu_s() const { return job_cpu_s_; }

 private:
  void Work();

  MapWindow window_;
  std::unique_ptr<MatchMap> map_;
  Eigen::Vector2d centre_ = Eigen::Vector2d::Zero();
  bool started_ = false;  // the tracking thread's view: a job was started, not yet taken
  bool waited_ = false;

  std::mutex mutex_;
  std::condition_variable wake_;
  // Guarded by mutex_.
  maps::PriorMapReader* job_map_ = nullptr;
  bool running_ = false;
  bool stopping_ = false;
  Status job_status_ = Status::Ok();
  double job_cpu_s_ = 0.0;

  std::thread worker_;  // last: started once everything above exists
};

}  // namespace flat2d::localization
