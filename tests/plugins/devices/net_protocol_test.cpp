// The net protocol (tacta_net_protocol.h) and the C client's passivity filter, without sockets.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <random>

#include "tacta_net_device.h"

namespace {

std::vector<unsigned char> datagram(uint32_t type, uint32_t session, uint32_t sequence,
                                    const void* payload) {
  std::vector<unsigned char> out(TNET_MAX_DATAGRAM);
  tnet_header h{};
  h.type = static_cast<uint16_t>(type);
  h.session = session;
  h.sequence = sequence;
  h.sender_time_ns = 123456789012345ull;
  uint32_t size = tnet_encode_header(out.data(), h);
  if (type == TNET_STATE)
    size += tnet_encode_state(out.data() + size, static_cast<const tnet_state*>(payload));
  if (type == TNET_FORCE)
    size += tnet_encode_force(out.data() + size, static_cast<const tnet_force*>(payload));
  out.resize(size);
  return out;
}

TEST(NetProtocol, StateRoundTripsBitForBit) {
  const tnet_state s{{0.1, -0.2, 0.3}, {1, 0, 0, 0}, {1e-3, 2e-3, -3e-3}, 5, 0};
  const auto d = datagram(TNET_STATE, 42, 7, &s);
  ASSERT_EQ(d.size(), TNET_HEADER_SIZE + TNET_STATE_SIZE);
  tnet_header h{};
  ASSERT_EQ(tnet_decode_header(d.data(), d.size(), &h), TNET_OK);
  EXPECT_EQ(h.session, 42u);
  EXPECT_EQ(h.sequence, 7u);
  EXPECT_EQ(h.sender_time_ns, 123456789012345ull);
  tnet_state back{};
  ASSERT_EQ(tnet_decode_state(d.data() + TNET_HEADER_SIZE, &back), TNET_OK);
  EXPECT_EQ(std::memcmp(back.position, s.position, sizeof s.position), 0);
  EXPECT_EQ(back.velocity[2], s.velocity[2]);
  EXPECT_EQ(back.buttons, 5u);
}

TEST(NetProtocol, RefusesMalformedDatagrams) {
  const tnet_state s{{0, 0, 0}, {1, 0, 0, 0}, {0, 0, 0}, 0, 0};
  auto d = datagram(TNET_STATE, 1, 1, &s);
  tnet_header h{};
  EXPECT_EQ(tnet_decode_header(d.data(), 10, &h), TNET_ERR_SHORT);
  EXPECT_EQ(tnet_decode_header(d.data(), d.size() - 1, &h), TNET_ERR_SHORT);
  auto bad = d;
  bad[0] ^= 0xFF;
  EXPECT_EQ(tnet_decode_header(bad.data(), bad.size(), &h), TNET_ERR_MAGIC);
  bad = d;
  bad[4] = 2;
  EXPECT_EQ(tnet_decode_header(bad.data(), bad.size(), &h), TNET_ERR_VERSION);
  bad = d;
  bad[6] = 9;
  EXPECT_EQ(tnet_decode_header(bad.data(), bad.size(), &h), TNET_ERR_TYPE);
  bad = d;
  bad[36] = 12;  // a payload size that does not fit STATE
  EXPECT_EQ(tnet_decode_header(bad.data(), bad.size(), &h), TNET_ERR_TYPE);
  tnet_state nan_state = s;
  nan_state.position[1] = std::nan("");
  auto n = datagram(TNET_STATE, 1, 1, &nan_state);
  tnet_state out{};
  EXPECT_EQ(tnet_decode_state(n.data() + TNET_HEADER_SIZE, &out), TNET_ERR_VALUE);
  tnet_state squashed = s;
  squashed.orientation[0] = 0.5;  // |q| = 0.5
  n = datagram(TNET_STATE, 1, 1, &squashed);
  EXPECT_EQ(tnet_decode_state(n.data() + TNET_HEADER_SIZE, &out), TNET_ERR_VALUE);
}

TEST(NetProtocol, SequenceCheckOrdersAcrossTheWrap) {
  EXPECT_EQ(tnet_sequence_check(5, 0, 0), 1);
  EXPECT_EQ(tnet_sequence_check(6, 5, 1), 1);
  EXPECT_EQ(tnet_sequence_check(5, 5, 1), 0);
  EXPECT_EQ(tnet_sequence_check(4, 5, 1), -1);
  EXPECT_EQ(tnet_sequence_check(2, 0xFFFFFFFEu, 1), 1);
  EXPECT_EQ(tnet_sequence_check(0xFFFFFFFEu, 2, 1), -1);
}

TEST(NetClient, DropsDuplicateOlderAndForeignForces) {
  tacta_net_device d{};
  d.session = 9;
  d.watchdog_s = 1.0;
  const tnet_force f{{0, 1, 0}, {0, 0, 0}, 0.5, 0.7, 0, 0};
  EXPECT_EQ(tacta_net_accept(&d, datagram(TNET_FORCE, 9, 10, &f).data(),
                             TNET_HEADER_SIZE + TNET_FORCE_SIZE, 1),
            1);
  EXPECT_EQ(tacta_net_accept(&d, datagram(TNET_FORCE, 9, 10, &f).data(),
                             TNET_HEADER_SIZE + TNET_FORCE_SIZE, 2),
            0);
  EXPECT_EQ(tacta_net_accept(&d, datagram(TNET_FORCE, 9, 8, &f).data(),
                             TNET_HEADER_SIZE + TNET_FORCE_SIZE, 3),
            0);
  EXPECT_EQ(tacta_net_accept(&d, datagram(TNET_FORCE, 8, 11, &f).data(),
                             TNET_HEADER_SIZE + TNET_FORCE_SIZE, 4),
            0);
  EXPECT_EQ(d.received, 1u);
  EXPECT_EQ(d.dropped, 2u);
  EXPECT_EQ(d.malformed, 1u);
  EXPECT_DOUBLE_EQ(tacta_net_remote_budget(&d), 0.5);
}

// Random forces and a random hand, with and without a remote budget. The hand moves v dt plus a
// miss of up to kMiss per axis that the filter cannot foresee (acceleration, jitter, encoder
// noise). The filter's ledger is the exact work of the held forces, recomputed here; it never
// goes below zero (rounding aside): the reserve covers every miss (without it: below zero within
// a few ticks). The energy returned in sampled power (how the simulation counts the remote
// budget) never passes the remote budget; no force passes the peak.
TEST(NetClient, PassivityFilterKeepsTheExactLedgerAndTheBudget) {
  constexpr double kPeak = 3.3, kMiss = 2e-5;  // N, m
  std::mt19937 rng(3);
  std::normal_distribution<double> force(0.0, 3.0), speed(0.0, 0.05);
  std::uniform_real_distribution<double> miss(-kMiss, kMiss);
  for (int use_remote = 0; use_remote < 2; ++use_remote) {
    tacta_net_passivity p{};
    tacta_net_passivity_reset(&p);
    p.use_remote = use_remote;
    double remote = 0.0, x[3] = {0, 0, 0}, exact = 0.0, returned = 0.0;
    for (int n = 0; n < 20000; ++n) {
      const double v[3] = {speed(rng), speed(rng), speed(rng)};
      const double wanted[3] = {force(rng), force(rng), force(rng)};
      remote += 1e-5 * std::abs(force(rng));  // the environment returns a little now and then
      double out[3];
      tacta_net_passivity_filter(&p, x, v, 1e-3, remote, wanted, kPeak, out);
      ASSERT_LE(std::hypot(out[0], out[1], out[2]), kPeak + 1e-12);
      double work = 0.0, sampled = 0.0;
      for (int a = 0; a < 3; ++a) {
        const double moved = v[a] * 1e-3 + miss(rng);
        work += out[a] * moved;
        sampled += out[a] * v[a] * 1e-3;
        x[a] += moved;
      }
      exact -= work;
      returned += std::max(sampled, 0.0);
      ASSERT_GE(exact, -1e-12) << "tick " << n;
      if (use_remote) {
        ASSERT_LE(returned, remote + 1e-12) << "tick " << n;
      }
    }
    const double still[3] = {0, 0, 0};
    double unused[3];
    tacta_net_passivity_filter(&p, x, still, 1e-3, remote, still, kPeak,
                               unused);  // charges the last tick
    EXPECT_NEAR(tacta_net_passivity_ledger(&p), exact, 1e-12);
    EXPECT_GT(p.dissipated, 0.0);
  }
}

}  // namespace
