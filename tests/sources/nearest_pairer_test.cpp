// The online colour-depth pairing of bags: the rule TumSource applies to a folder's lists.
#include "rgbdvo/sources/nearest_pairer.hpp"

#include <catch2/catch.hpp>
#include <vector>

using namespace rgbdvo;

namespace {

// Pairs as (colour id, depth id), feeding the messages in the given order.
struct Message {
  bool color;
  double t;
  int id;
};
std::vector<std::pair<int, int>> Pair(const std::vector<Message>& messages, double max_dt,
                                      int* unpaired) {
  NearestPairer<int> pairer(max_dt);
  std::vector<std::pair<int, int>> out;
  for (const Message& m : messages) {
    if (m.color)
      pairer.AddColor(m.t, m.id);
    else
      pairer.AddDepth(m.t, m.id);
    for (const auto& p : pairer.Take(false)) out.push_back({p.color, p.depth});
  }
  for (const auto& p : pairer.Take(true)) out.push_back({p.color, p.depth});
  *unpaired = pairer.unpaired();
  return out;
}

}  // namespace

TEST_CASE("Nearest pairing takes the nearest depth image, the later on a tie, reusing depth") {
  // Colour 1 at 0.100: depth 10 (0.095) is nearer than 11 (0.110). Colour 2 at 0.120: 11.
  // Colour 3 at 0.135 ties between 11 (0.125) and 12 (0.145): the later, 12.
  // Colour 4 at 0.150 also takes 12 (reused). Colour 5 at 0.300: nothing within 0.02 s.
  const std::vector<Message> messages = {
      {false, 0.095, 10}, {true, 0.100, 1},   {true, 0.120, 2}, {false, 0.125, 11},
      {true, 0.135, 3},   {false, 0.145, 12}, {true, 0.150, 4}, {true, 0.300, 5},
  };
  int unpaired = 0;
  const auto pairs = Pair(messages, 0.02, &unpaired);
  const std::vector<std::pair<int, int>> expected = {{1, 10}, {2, 11}, {3, 12}, {4, 12}};
  CHECK(pairs == expected);
  CHECK(unpaired == 1);
}

TEST_CASE("Nearest pairing waits for depth recorded out of order within the window") {
  // Depth 10 (1.001) is recorded after depth 11 (1.015), 14 ms out of order: colour 1 still
  // gets the nearer one.
  const std::vector<Message> messages = {
      {true, 1.000, 1},   {false, 1.015, 11}, {false, 1.001, 10}, {true, 1.033, 2},
      {false, 1.034, 12}, {true, 1.066, 3},   {false, 1.067, 13},
  };
  int unpaired = 0;
  const auto pairs = Pair(messages, 0.02, &unpaired);
  const std::vector<std::pair<int, int>> expected = {{1, 10}, {2, 12}, {3, 13}};
  CHECK(pairs == expected);
  CHECK(unpaired == 0);
}

TEST_CASE("Nearest pairing holds only the images of the window") {
  NearestPairer<int> pairer(0.02);
  int decided = 0;
  for (int i = 0; i < 1000; ++i) {
    pairer.AddColor(i / 30.0, i);
    pairer.AddDepth(i / 30.0 + 0.005, i);
    for (const auto& p : pairer.Take(false)) {
      CHECK(p.color == p.depth);
      ++decided;
    }
    // Everything older than the window has been decided.
    CHECK(decided >= i - 1);
  }
  decided += static_cast<int>(pairer.Take(true).size());
  CHECK(decided == 1000);
  CHECK(pairer.unpaired() == 0);
}
