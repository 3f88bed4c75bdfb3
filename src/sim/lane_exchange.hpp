#pragma once
// What the threads of run_interleaved that share a LaneExchange know of each other, and each
// call's seat at it: how droplets are handed from a busy thread to one with idle lanes.
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <optional>
#include <vector>

#include "interleaved.hpp"
#include "run_stepper.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {

// A lane of run_interleaved: the droplet and its run's book-keeping. (RunStepper holds a reference,
// so lanes move by re-emplacing.)
struct Lane {
  DropletJob job;
  std::optional<RunStepper> run;
};

inline void move_lane(Lane& from, Lane& to) {
  to.job = from.job;
  to.run.emplace(std::move(*from.run));
  from.run.reset();
}

constexpr int kNoneStarving = 1 << 20;

// What the threads sharing lanes know of each other: for each seat (a run_interleaved call) how
// many droplets it steps and whether next() left it lanes it could not fill, and one droplet on
// offer.
struct LaneExchange::Impl {
  struct Seat {
    bool present = true, starving = false;
    int busy = 0;
  };
  std::mutex m;
  std::condition_variable cv;
  std::vector<Seat> seats;
  std::optional<Lane> offer;
  int offer_busy = 0;  // droplets its giver steps without it; only a seat stepping fewer takes it
  int waiting = 0;
  // Read at every step without the lock: the fewest droplets stepped by a starving seat, and
  // whether a droplet is on offer.
  std::atomic<int> min_starving{kNoneStarving};
  std::atomic<bool> offered{false};
  std::atomic<std::int64_t> handovers{0};

  void update_min() {  // under m
    int lo = kNoneStarving;
    for (const Seat& s : seats)
      if (s.present && s.starving) lo = std::min(lo, s.busy);
    min_starving.store(lo, std::memory_order_relaxed);
  }
};

// One run_interleaved call's place at a LaneExchange (none without one: then it does nothing). The
// checks made at every step read two atomics; everything else takes the lock, and happens only when
// a droplet starts, ends or moves.
class LaneExchangeSeat {
 public:
  LaneExchangeSeat(LaneExchange* exchange, int lanes) : x_(exchange ? exchange->impl() : nullptr), lanes_(lanes) {
    if (!x_) return;
    std::lock_guard lock(x_->m);
    seat_ = x_->seats.size();
    x_->seats.emplace_back();
  }
  ~LaneExchangeSeat() {
    if (!x_) return;
    std::lock_guard lock(x_->m);
    x_->seats[seat_] = {false, false, 0};
    x_->update_min();
    x_->cv.notify_all();
  }
  LaneExchangeSeat(const LaneExchangeSeat&) = delete;
  LaneExchangeSeat& operator=(const LaneExchangeSeat&) = delete;

  /// After the lanes are filled: `busy` droplets stepped; lanes left idle mean next() had none.
  void publish(int busy) {
    if (!x_ || busy == busy_) return;
    std::lock_guard lock(x_->m);
    set(busy, busy < lanes_);
  }
  /// Whether a starving thread steps at least two droplets fewer than `busy` and none is on offer.
  bool should_give(int busy) const {
    return x_ && busy >= 2 && !x_->offered.load(std::memory_order_relaxed) &&
           x_->min_starving.load(std::memory_order_relaxed) <= busy - 2;
  }
  /// Offers the droplet in `lane` (this thread steps `busy` with it); false if that no longer fits.
  bool give(Lane& lane, int busy) {
    std::lock_guard lock(x_->m);
    if (x_->offer || x_->min_starving.load(std::memory_order_relaxed) > busy - 2) return false;
    x_->offer.emplace();
    move_lane(lane, *x_->offer);
    x_->offer_busy = busy - 1;
    x_->offered.store(true, std::memory_order_relaxed);
    set(busy - 1, busy - 1 < lanes_);
    x_->cv.notify_all();
    return true;
  }
  bool offer_waiting() const { return x_ && x_->offered.load(std::memory_order_relaxed); }
  /// Takes the droplet on offer into the idle `lane` if its giver steps more than `busy`, the
  /// droplets this thread steps without it (so a giver does not take its offer back).
  bool take(Lane& lane, int busy) {
    if (!x_) return false;
    std::lock_guard lock(x_->m);
    return take_locked(lane, busy);
  }
  /// With every lane idle, before next() may wait: takes a droplet on offer, or else says this
  /// thread starves no more, so that none is offered to it while it waits in next().
  bool take_or_withdraw(Lane& lane) {
    if (!x_) return false;
    std::lock_guard lock(x_->m);
    if (take_locked(lane, 0)) return true;
    set(0, false);
    return false;
  }
  /// With every lane idle and next() out of droplets: waits for a droplet on offer; false once no
  /// other thread steps two or more (none will be offered).
  bool wait_for_offer(Lane& lane) {
    if (!x_) return false;
    std::unique_lock lock(x_->m);
    set(0, true);
    ++x_->waiting;
    x_->cv.wait(lock, [&] {
      if (x_->offer) return true;
      for (std::size_t i = 0; i < x_->seats.size(); ++i)
        if (i != seat_ && x_->seats[i].present && x_->seats[i].busy >= 2) return false;
      return true;
    });
    --x_->waiting;
    return take_locked(lane, 0);
  }

 private:
  void set(int busy, bool starving) {  // under the lock
    busy_ = busy;
    x_->seats[seat_].busy = busy;
    x_->seats[seat_].starving = starving;
    x_->update_min();
    if (x_->waiting > 0) x_->cv.notify_all();
  }
  bool take_locked(Lane& lane, int busy) {
    if (!x_->offer || busy >= x_->offer_busy) return false;
    move_lane(*x_->offer, lane);
    x_->offer.reset();
    x_->offered.store(false, std::memory_order_relaxed);
    x_->handovers.fetch_add(1, std::memory_order_relaxed);
    set(busy + 1, busy + 1 < lanes_);
    return true;
  }

  LaneExchange::Impl* x_;
  const int lanes_;
  std::size_t seat_ = 0;
  int busy_ = 0;  // as last published
};

}  // namespace softdrop
