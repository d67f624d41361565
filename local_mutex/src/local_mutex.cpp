#include "local_mutex/local_mutex.h"

#include <algorithm>

namespace local_mutex {

const char* StateName(State s) {
  switch (s) {
    case State::kReleased:
      return "RELEASED";
    case State::kWanted:
      return "WANTED";
    case State::kSilent:
      return "SILENT";
    case State::kHeld:
      return "HELD";
  }
  return "?";
}

const char* EventKindName(MutexEvent::Kind k) {
  switch (k) {
    case MutexEvent::Kind::kStateChange:
      return "state";
    case MutexEvent::Kind::kSent:
      return "sent";
    case MutexEvent::Kind::kHeard:
      return "heard";
    case MutexEvent::Kind::kNoise:
      return "noise";
    case MutexEvent::Kind::kMalformed:
      return "malformed";
    case MutexEvent::Kind::kDuplicateId:
      return "duplicate_id";
    case MutexEvent::Kind::kEcho:
      return "echo";
  }
  return "?";
}

LocalMutex::LocalMutex(const MutexOptions& options, Send send, Gaussian gaussian)
    : options_(options), send_(std::move(send)), gaussian_(std::move(gaussian)), rng_(options.seed) {
  ValidateMutexOptions(options_);
  if (!gaussian_) {
    gaussian_ = [this](double mean, double sd) {
      return sd > 0.0 ? std::normal_distribution<double>(mean, sd)(rng_) : mean;
    };
  }
}

double LocalMutex::Draw(double mean, double sd) { return std::max(0.1 * mean, gaussian_(mean, sd)); }

void LocalMutex::Notify(MutexEvent::Kind kind, double now, const Message& m) {
  if (!observer_) return;
  MutexEvent e;
  e.kind = kind;
  e.time = now;
  e.state = state_;
  e.clock = clock_;
  e.message = m;
  observer_(e);
}

void LocalMutex::Enter(State s, double now) {
  state_ = s;
  state_since_ = now;
  Notify(MutexEvent::Kind::kStateChange, now);
}

bool LocalMutex::Request(double now) {
  if (state_ != State::kReleased) return false;
  request_time_ = clock_;
  grab_deadline_ = now + options_.grab_time;
  if (now - last_request_heard_at_ < options_.grab_time && Precedes(last_request_heard_, request())) {
    // Someone asked before us, recently: defer from when we heard it (POSTPONEREQUEST).
    next_transmit_ =
        std::max(now, last_request_heard_at_ + options_.grab_time + Draw(options_.request_mean, options_.request_sd));
    grab_deadline_ = next_transmit_ + options_.grab_time;
    Enter(State::kSilent, now);
    return true;
  }
  next_transmit_ = now + Draw(options_.request_mean, options_.request_sd);
  Enter(State::kWanted, now);
  return true;
}

bool LocalMutex::Release(double now) {
  if (state_ == State::kReleased) return false;
  Enter(State::kReleased, now);
  return true;
}

void LocalMutex::Transmit(MessageType type, LamportTime stamp, double now) {
  Message m;
  m.robot_id = static_cast<std::uint8_t>(options_.robot_id);
  m.type = type;
  m.time = stamp;
  ++clock_;  // sending is an event
  ++counters_.sent;
  last_sent_ = m;
  last_sent_at_ = now;
  send_(Encode(m));
  Notify(MutexEvent::Kind::kSent, now, m);
}

void LocalMutex::PostponeGrab(double now) {
  grab_deadline_ = now + options_.grab_time;
  // Never take the lock while silent: t_grab after the request that ends the silence.
  if (state_ == State::kSilent) grab_deadline_ = std::max(grab_deadline_, next_transmit_ + options_.grab_time);
}

void LocalMutex::OnSound(double now) {
  if (state_ == State::kWanted || state_ == State::kSilent) PostponeGrab(now);
}

void LocalMutex::HearNoise(double now) {
  ++clock_;
  ++counters_.noise;
  OnSound(now);
  Notify(MutexEvent::Kind::kNoise, now);
}

void LocalMutex::HearPacket(const std::vector<std::uint8_t>& packet, double now) {
  const std::optional<Message> m = Decode(packet);
  if (!m) {
    ++counters_.malformed;
    ++clock_;
    OnSound(now);
    Notify(MutexEvent::Kind::kMalformed, now);
    return;
  }
  if (m->robot_id == options_.robot_id) {
    if (*m == last_sent_ && now - last_sent_at_ <= options_.echo_window) {
      ++counters_.echoes;
      Notify(MutexEvent::Kind::kEcho, now, *m);
      return;
    }
    ++counters_.duplicate_ids;
    ++clock_;
    OnSound(now);
    Notify(MutexEvent::Kind::kDuplicateId, now, *m);
    return;
  }

  ++counters_.heard;
  if (m->type == MessageType::kRequest) {
    last_request_heard_ = {m->time, m->robot_id};
    last_request_heard_at_ = now;
  }
  if (LamportAfter(m->time, clock_)) clock_ = m->time;
  ++clock_;
  if (state_ == State::kWanted || state_ == State::kSilent) {
    if (m->type == MessageType::kLock) {
      // SCHEDULEREQUEST: someone holds the lock; keep asking so we are next.
      next_transmit_ = std::min(next_transmit_, now + Draw(options_.request_mean, options_.request_sd));
    }
    PostponeGrab(now);  // after the next request is known: SILENT's floor depends on it
    if (m->type == MessageType::kRequest && Precedes({m->time, m->robot_id}, request())) {
      // POSTPONEREQUEST: the other robot asked first; let it have the lock.
      next_transmit_ = now + options_.grab_time + Draw(options_.request_mean, options_.request_sd);
      grab_deadline_ = next_transmit_ + options_.grab_time;
      if (state_ != State::kSilent) {
        Notify(MutexEvent::Kind::kHeard, now, *m);
        Enter(State::kSilent, now);
        return;
      }
    }
  }
  Notify(MutexEvent::Kind::kHeard, now, *m);
}

void LocalMutex::Tick(double now) {
  if (state_ == State::kWanted && now >= grab_deadline_) {
    ++counters_.grants;
    Enter(State::kHeld, now);
    next_transmit_ = now;  // announce at once
  }
  if (now < next_transmit_) return;
  switch (state_) {
    case State::kSilent:
      Transmit(MessageType::kRequest, request_time_, now);
      next_transmit_ = now + Draw(options_.request_mean, options_.request_sd);
      Enter(State::kWanted, now);
      break;
    case State::kWanted:
      Transmit(MessageType::kRequest, request_time_, now);
      next_transmit_ = now + Draw(options_.request_mean, options_.request_sd);
      break;
    case State::kHeld:
      Transmit(MessageType::kLock, clock_, now);
      next_transmit_ = now + Draw(options_.lock_mean, options_.lock_sd);
      break;
    case State::kReleased:
      break;
  }
}

}  // namespace local_mutex
