#include "rgbdvo/util/bounded_queue.hpp"

#include <catch2/catch.hpp>
#include <optional>
#include <thread>

using namespace rgbdvo;
using std::chrono::milliseconds;

TEST_CASE("BoundedQueue keeps the newest items and counts the dropped ones") {
  BoundedQueue<int> q(2);
  int drops = 0;
  for (int i = 0; i < 10; ++i) drops += q.Push(i) ? 1 : 0;
  CHECK(drops == 8);
  CHECK(q.dropped() == 8);
  CHECK(q.size() == 2);
  CHECK(q.Pop(milliseconds(0)) == 8);
  CHECK(q.Pop(milliseconds(0)) == 9);
  CHECK(!q.Pop(milliseconds(1)));  // empty: times out
}

TEST_CASE("BoundedQueue::PushWait waits for room instead of dropping") {
  BoundedQueue<int> q(1);
  CHECK(q.PushWait(1, milliseconds(0)));
  CHECK(!q.PushWait(2, milliseconds(1)));  // full: times out, nothing dropped
  CHECK(q.dropped() == 0);
  std::optional<int> taken;  // checked on this thread: Catch's assertions are not thread-safe
  std::thread consumer([&] { taken = q.Pop(milliseconds(5000)); });
  CHECK(q.PushWait(3, milliseconds(5000)));  // room once the consumer took one
  consumer.join();
  CHECK(taken == 1);
  CHECK(q.Pop(milliseconds(0)) == 3);
}

TEST_CASE("BoundedQueue::Close wakes the consumer and keeps queued items") {
  BoundedQueue<int> q(3);
  q.Push(7);
  q.Close();
  CHECK(!q.PushWait(8, milliseconds(1000)));  // refused at once, not after the timeout
  CHECK(!q.closed_and_empty());
  CHECK(q.Pop(milliseconds(0)) == 7);
  CHECK(q.closed_and_empty());
  CHECK(!q.Pop(milliseconds(1000)));
  CHECK_THROWS_AS(BoundedQueue<int>(0), std::invalid_argument);
}
