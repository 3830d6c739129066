// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Flow routing: the priority-flood + epsilon fill (a closed basin fills to its
// spill height within a few ulps, surfaces without depressions are left as
// they are), steepest-descent receivers strictly lower on the filled surface,
// an order with every receiver before its donors, drainage areas that add
// up, degenerate grids, determinism and bad input.

#include <strata/Error.h>
#include <strata/Sha256.h>
#include <strata/terrain/FlowRouting.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace {

using namespace strata::terrain;

std::size_t at(int width, int x, int z)
{
    return std::size_t(z) * std::size_t(width) + std::size_t(x);
}

bool isEdge(const FlowRouting& r, std::size_t c)
{
    const int x = int(c % std::size_t(r.width)), z = int(c / std::size_t(r.width));
    return x == 0 || z == 0 || x == r.width - 1 || z == r.height - 1;
}

/// `value` raised by `steps` representable doubles.
double ulpsAbove(double value, int steps)
{
    for (int i = 0; i < steps; ++i) value = std::nextafter(value, std::numeric_limits<double>::infinity());
    return value;
}

/// Heights from a small deterministic generator: smooth hills plus noise
/// plus a few pits, so the fill has work to do.
std::vector<double> bumpyHeights(int width, int height, std::uint64_t seed)
{
    std::vector<double> h(std::size_t(width) * std::size_t(height));
    std::uint64_t s = seed;
    for (int z = 0; z < height; ++z) {
        for (int x = 0; x < width; ++x) {
            s = s * 6364136223846793005ull + 1442695040888963407ull;
            const double noise = double(s >> 11) * 0x1p-53;
            h[at(width, x, z)] = 20.0 * std::sin(x * 0.21) * std::cos(z * 0.17) + 3.0 * noise +
                                 ((x * 7 + z * 3) % 23 == 0 ? -6.0 : 0.0) + (z % 5 == 0 ? 1.0 : 0.0);
        }
    }
    return h;
}

/// The invariants every routing must satisfy: filled >= heights; edge cells
/// drain to themselves; every interior cell to one of its 8 neighbours that
/// is strictly lower on `filled` and no neighbour is steeper; `order` is a
/// permutation with every receiver before its donors, edges first and the
/// interior in non-decreasing filled order; the edge cells' drainage areas
/// add up to the grid's area.
void expectValidRouting(const FlowRouting& r, const std::vector<double>& heights, double cellSize)
{
    const std::size_t n = heights.size();
    ASSERT_EQ(r.filled.size(), n);
    ASSERT_EQ(r.receiver.size(), n);
    ASSERT_EQ(r.order.size(), n);
    for (std::size_t c = 0; c < n; ++c) EXPECT_GE(r.filled[c], heights[c]) << "cell " << c;

    for (std::size_t c = 0; c < n; ++c) {
        const std::uint32_t to = r.receiver[c];
        if (isEdge(r, c)) {
            EXPECT_EQ(to, c) << "edge cell " << c;
            continue;
        }
        const int x = int(c % std::size_t(r.width)), z = int(c / std::size_t(r.width));
        const int tx = int(to % std::size_t(r.width)), tz = int(to / std::size_t(r.width));
        ASSERT_NE(to, c) << "interior cell " << c << " has no receiver";
        ASSERT_LE(std::abs(tx - x), 1);
        ASSERT_LE(std::abs(tz - z), 1);
        EXPECT_LT(r.filled[to], r.filled[c]) << "cell " << c;
        const double steepest = (r.filled[c] - r.filled[to]) / (tx != x && tz != z ? std::sqrt(2.0) : 1.0);
        for (int dz = -1; dz <= 1; ++dz) {
            for (int dx = -1; dx <= 1; ++dx) {
                if (dx == 0 && dz == 0) continue;
                const double slope =
                    (r.filled[c] - r.filled[at(r.width, x + dx, z + dz)]) / (dx != 0 && dz != 0 ? std::sqrt(2.0) : 1.0);
                EXPECT_LE(slope, steepest * (1.0 + 1e-15)) << "cell " << c << " has a steeper neighbour";
            }
        }
    }

    std::vector<std::int64_t> position(n, -1);
    for (std::size_t i = 0; i < n; ++i) {
        ASSERT_LT(r.order[i], n);
        ASSERT_EQ(position[r.order[i]], -1) << "cell " << r.order[i] << " twice in order";
        position[r.order[i]] = std::int64_t(i);
    }
    bool seenInterior = false;
    double lastFilled = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t c = r.order[i];
        if (isEdge(r, c)) {
            EXPECT_FALSE(seenInterior) << "edge cell " << c << " after an interior cell";
        } else {
            seenInterior = true;
            EXPECT_GE(r.filled[c], lastFilled);
            lastFilled = r.filled[c];
        }
        EXPECT_LE(position[r.receiver[c]], position[c]) << "cell " << c << " before its receiver";
    }

    const std::vector<double> area = drainageArea(r, cellSize);
    ASSERT_EQ(area.size(), n);
    double edgeSum = 0.0;
    for (std::size_t c = 0; c < n; ++c) {
        EXPECT_GE(area[c], cellSize * cellSize);
        if (isEdge(r, c)) edgeSum += area[c];
    }
    EXPECT_NEAR(edgeSum, double(n) * cellSize * cellSize, 1e-9 * double(n) * cellSize * cellSize);
}

/// A 21 × 21 bowl: floor 1 + 0.1·r inside a rim (height 20) at Chebyshev
/// distance 7 from the centre, one notch in the rim at height 12, flat
/// ground at 5 outside.
constexpr int BOWL = 21, BOWL_CENTRE = 10, RIM = 7;
constexpr int NOTCH_X = BOWL_CENTRE + RIM, NOTCH_Z = BOWL_CENTRE;
constexpr double SPILL = 12.0;

std::vector<double> bowlHeights()
{
    std::vector<double> h(BOWL * BOWL);
    for (int z = 0; z < BOWL; ++z) {
        for (int x = 0; x < BOWL; ++x) {
            const int d = std::max(std::abs(x - BOWL_CENTRE), std::abs(z - BOWL_CENTRE));
            const double r = std::hypot(x - BOWL_CENTRE, z - BOWL_CENTRE);
            h[at(BOWL, x, z)] = d < RIM ? 1.0 + 0.1 * r : d == RIM ? 20.0 : 5.0;
        }
    }
    h[at(BOWL, NOTCH_X, NOTCH_Z)] = SPILL;
    return h;
}

TEST(FlowRouting, ClosedBasinFillsToItsSpillHeight)
{
    const std::vector<double> heights = bowlHeights();
    const FlowRouting r = routeFlow(heights, BOWL, BOWL, 2.0);
    expectValidRouting(r, heights, 2.0);

    EXPECT_EQ(r.filled[at(BOWL, NOTCH_X, NOTCH_Z)], SPILL);
    int inside = 0;
    for (int z = 0; z < BOWL; ++z) {
        for (int x = 0; x < BOWL; ++x) {
            const std::size_t c = at(BOWL, x, z);
            const int d = std::max(std::abs(x - BOWL_CENTRE), std::abs(z - BOWL_CENTRE));
            if (d < RIM) {
                ++inside;
                // At most one step per cell on the way from the notch.
                EXPECT_GT(r.filled[c], SPILL) << x << ", " << z;
                EXPECT_LE(r.filled[c], ulpsAbove(SPILL, 2 * RIM)) << x << ", " << z;
            } else if (d > RIM) {
                EXPECT_LE(r.filled[c], ulpsAbove(heights[c], 4)) << x << ", " << z;
            } else if (c != at(BOWL, NOTCH_X, NOTCH_Z)) {
                EXPECT_EQ(r.filled[c], heights[c]) << "rim " << x << ", " << z;
            }
        }
    }
    // Every cell of the bowl leaves through the notch: its area is the
    // bowl's and its own (the rim drains outwards, the notch is above the
    // ground outside).
    const std::vector<double> area = drainageArea(r, 2.0);
    EXPECT_DOUBLE_EQ(area[at(BOWL, NOTCH_X, NOTCH_Z)], (inside + 1) * 4.0);
    std::size_t c = at(BOWL, BOWL_CENTRE, BOWL_CENTRE);
    bool passedNotch = false;
    while (r.receiver[c] != c) {
        passedNotch = passedNotch || c == at(BOWL, NOTCH_X, NOTCH_Z);
        c = r.receiver[c];
    }
    EXPECT_TRUE(passedNotch);
}

TEST(FlowRouting, ConeDrainsRadially)
{
    constexpr int N = 33, APEX = 16;
    std::vector<double> heights(N * N);
    for (int z = 0; z < N; ++z)
        for (int x = 0; x < N; ++x) heights[at(N, x, z)] = 100.0 - 2.0 * std::hypot(x - APEX, z - APEX);
    const FlowRouting r = routeFlow(heights, N, N, 1.0);
    expectValidRouting(r, heights, 1.0);
    EXPECT_EQ(r.filled, heights) << "a cone has no depression to fill";
    for (std::size_t c = 0; c < heights.size(); ++c) {
        if (isEdge(r, c)) continue;
        const std::size_t to = r.receiver[c];
        const double from = std::hypot(int(c % N) - APEX, int(c / N) - APEX);
        const double toDistance = std::hypot(int(to % N) - APEX, int(to / N) - APEX);
        EXPECT_GT(toDistance, from) << "cell " << c << " drains towards the apex";
        EXPECT_LT(heights[to], heights[c]);
    }
    const std::vector<double> area = drainageArea(r, 1.0);
    EXPECT_EQ(area[at(N, APEX, APEX)], 1.0);
}

TEST(FlowRouting, TiltedPlaneDrainsDownTheSlopeAndAccumulates)
{
    constexpr int W = 40, H = 12;
    constexpr double CELL = 3.0;
    std::vector<double> heights(W * H);
    for (int z = 0; z < H; ++z)
        for (int x = 0; x < W; ++x) heights[at(W, x, z)] = 50.0 - 0.5 * x;
    const FlowRouting r = routeFlow(heights, W, H, CELL);
    expectValidRouting(r, heights, CELL);
    EXPECT_EQ(r.filled, heights);
    const std::vector<double> area = drainageArea(r, CELL);
    for (int z = 1; z < H - 1; ++z) {
        for (int x = 1; x < W - 1; ++x) {
            EXPECT_EQ(r.receiver[at(W, x, z)], at(W, x + 1, z));
            EXPECT_EQ(receiverDistance(r, at(W, x, z), CELL), CELL);
            EXPECT_DOUBLE_EQ(area[at(W, x, z)], x * CELL * CELL) << x << ", " << z;
        }
        EXPECT_DOUBLE_EQ(area[at(W, W - 1, z)], (W - 1) * CELL * CELL);
        EXPECT_EQ(receiverDistance(r, at(W, W - 1, z), CELL), 0.0);
    }
}

TEST(FlowRouting, DiagonalReceiverDistance)
{
    // A plane falling towards +x and +z: the diagonal is steepest.
    constexpr int N = 6;
    std::vector<double> heights(N * N);
    for (int z = 0; z < N; ++z)
        for (int x = 0; x < N; ++x) heights[at(N, x, z)] = -double(x + z);
    const FlowRouting r = routeFlow(heights, N, N, 2.0);
    expectValidRouting(r, heights, 2.0);
    EXPECT_EQ(r.receiver[at(N, 2, 2)], at(N, 3, 3));
    EXPECT_DOUBLE_EQ(receiverDistance(r, at(N, 2, 2), 2.0), 2.0 * std::sqrt(2.0));
}

TEST(FlowRouting, FlatGetsAGradientOfUlps)
{
    constexpr int W = 50, H = 30;
    const std::vector<double> heights(W * H, 7.5);
    const FlowRouting r = routeFlow(heights, W, H, 1.0);
    expectValidRouting(r, heights, 1.0);
    for (std::size_t c = 0; c < heights.size(); ++c) EXPECT_LE(r.filled[c], ulpsAbove(7.5, W));
}

TEST(FlowRouting, BumpySurfacesAreRoutedConsistently)
{
    for (const std::uint64_t seed : {1ull, 2ull, 99ull}) {
        for (const auto& [w, h] : {std::pair{64, 48}, std::pair{3, 17}, std::pair{31, 3}}) {
            SCOPED_TRACE("seed " + std::to_string(seed) + ", " + std::to_string(w) + " x " + std::to_string(h));
            const std::vector<double> heights = bumpyHeights(w, h, seed);
            const FlowRouting r = routeFlow(heights, w, h, 1.5);
            expectValidRouting(r, heights, 1.5);
        }
    }
}

TEST(FlowRouting, GridsOneOrTwoCellsAcrossAreAllEdge)
{
    for (const auto& [w, h] : {std::pair{1, 1}, std::pair{1, 5}, std::pair{2, 7}, std::pair{5, 2}, std::pair{2, 2}}) {
        SCOPED_TRACE(std::to_string(w) + " x " + std::to_string(h));
        const std::vector<double> heights = bumpyHeights(w, h, 5);
        const FlowRouting r = routeFlow(heights, w, h, 2.0);
        expectValidRouting(r, heights, 2.0);
        EXPECT_EQ(r.filled, heights);
        for (std::size_t c = 0; c < heights.size(); ++c) {
            EXPECT_EQ(r.receiver[c], c);
            EXPECT_EQ(r.order[c], c);
        }
        const std::vector<double> area = drainageArea(r, 2.0);
        for (const double a : area) EXPECT_EQ(a, 4.0);
    }
}

TEST(FlowRouting, AGoldenSurfaceRoutesToTheRecordedBits)
{
    // Heights from integers and an LCG only (no libm), so the digest is the
    // routing's own: the same bits from every compiler and CPU (issue 39).
    // A change that moves them must say why and record the new digest.
    const int w = 80, h = 70;
    std::vector<double> heights(std::size_t(w) * std::size_t(h));
    std::uint64_t s = 42;
    for (int z = 0; z < h; ++z) {
        for (int x = 0; x < w; ++x) {
            s = s * 6364136223846793005ull + 1442695040888963407ull;
            heights[at(w, x, z)] = double((x * x * 7 + z * 13 + x * z) % 97) * 0.25 + 3.0 * double(s >> 11) * 0x1p-53 +
                                   ((x * 7 + z * 3) % 23 == 0 ? -6.0 : 0.0);
        }
    }
    const auto digest = [&] {
        const FlowRouting r = routeFlow(heights, w, h, 1.5);
        const std::vector<double> area = drainageArea(r, 1.5);
        std::string bytes;
        const auto append = [&bytes](const auto& v) {
            bytes.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(v[0]));
        };
        append(r.filled);
        append(r.receiver);
        append(r.order);
        append(area);
        return strata::sha256Hex(bytes);
    };
    const std::string first = digest();
    EXPECT_EQ(digest(), first);
    EXPECT_EQ(first, "288d68e95f9b410df0ddb17b9eb5a65f5dee99f093b98e1d306a2c21fe2c47ab");
}

/// The message of the strata::Error `f` throws ("" if none).
template <class F> std::string errorOf(F f)
{
    try {
        f();
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput);
        return e.what();
    }
    ADD_FAILURE() << "no strata::Error";
    return "";
}

TEST(FlowRouting, BadInputThrows)
{
    const std::vector<double> nine(9, 1.0);
    EXPECT_NE(errorOf([&] { routeFlow({}, 0, 3, 1.0); }).find(">= 1"), std::string::npos);
    EXPECT_NE(errorOf([&] { routeFlow(nine, 4, 3, 1.0); }).find("9 heights"), std::string::npos);
    EXPECT_NE(errorOf([&] { routeFlow(nine, 3, 3, 0.0); }).find("cell size"), std::string::npos);
    EXPECT_NE(errorOf([&] { routeFlow(nine, 3, 3, std::nan("")); }).find("cell size"), std::string::npos);
    std::vector<double> bad = nine;
    bad[at(3, 2, 1)] = std::numeric_limits<double>::infinity();
    EXPECT_NE(errorOf([&] { routeFlow(bad, 3, 3, 1.0); }).find("(x 2, z 1)"), std::string::npos);
}

} // namespace

// Multiple flow directions (the erode node's flow and water masks, issue 38:
// D8 drew rivers as 45° staircases). On a plane falling at 22.5° from the
// grid's axes, D8 sends every cell's water one way or the other, so the
// area across the flow jumps from cell to cell; multiple directions split
// it by slope and the area varies smoothly. Nothing is lost: the edge
// cells receive the grid's whole area. The same bits twice.
TEST(FlowRouting, MultipleFlowDirectionsFollowTheTrueGradient)
{
    const int n = 64;
    const double c = std::cos(0.3926990816987241), s = std::sin(0.3926990816987241);
    std::vector<double> heights(std::size_t(n) * n);
    for (int z = 0; z < n; ++z)
        for (int x = 0; x < n; ++x) heights[at(n, x, z)] = 100.0 - (c * x + s * z) * 2.0;
    const FlowRouting r = routeFlow(heights, n, n, 2.0);
    const std::vector<double> d8 = drainageArea(r, 2.0);
    const std::vector<double> mfd = multipleFlowArea(r, 2.0);
    // Across the flow: the cells of column 48 between rows 12 and 40.
    // The area there grows with z (longer flow paths from the upper edges):
    // smoothly with multiple directions (one direction of change), in
    // alternating jumps with D8.
    double jumpsD8 = 0.0, jumpsMfd = 0.0;
    int turnsD8 = 0, turnsMfd = 0;
    for (int z = 12; z < 40; ++z) {
        const double a = d8[at(n, 48, z + 1)] - d8[at(n, 48, z)], b = mfd[at(n, 48, z + 1)] - mfd[at(n, 48, z)];
        jumpsD8 += std::abs(a);
        jumpsMfd += std::abs(b);
        if (z > 12) {
            turnsD8 += (a > 0.0) != (d8[at(n, 48, z)] - d8[at(n, 48, z - 1)] > 0.0);
            turnsMfd += (b > 0.0) != (mfd[at(n, 48, z)] - mfd[at(n, 48, z - 1)] > 0.0);
        }
    }
    EXPECT_LT(jumpsMfd, 0.1 * jumpsD8) << "D8 " << jumpsD8 << ", multiple directions " << jumpsMfd;
    EXPECT_LE(turnsMfd, 1);
    EXPECT_GE(turnsD8, 8);
    // Conservation: what leaves through the edge is the whole grid.
    double outlets = 0.0;
    for (std::size_t i = 0; i < mfd.size(); ++i)
        if (isEdge(r, i)) outlets += mfd[i];
    EXPECT_NEAR(outlets, 4.0 * n * n, 1e-9 * 4.0 * n * n);
    EXPECT_EQ(multipleFlowArea(r, 2.0), mfd);
    // A larger exponent concentrates the flow: the widest spread of one
    // cell's water (exponent 1) carries less to the steepest neighbour.
    const std::vector<double> diffuse = multipleFlowArea(r, 2.0, 1);
    EXPECT_NE(diffuse, mfd);
    EXPECT_THROW(multipleFlowArea(r, 2.0, 0), strata::Error);
    EXPECT_THROW(multipleFlowArea(r, 2.0, 9), strata::Error);
}

// In a valley the channel gathers nearly what D8 gathers: the valley's
// mouth (the edge cells around it) and the channel above it carry over 90 %
// of what D8 sends to its one outlet (the rest leaves the first row of the
// hillslopes straight over the edge, which D8's one direction never does).
TEST(FlowRouting, MultipleFlowDirectionsGatherAValleyIntoItsChannel)
{
    const int n = 48;
    std::vector<double> heights(std::size_t(n) * n);
    // A V-shaped valley along x = 24, falling towards z = 0.
    for (int z = 0; z < n; ++z)
        for (int x = 0; x < n; ++x) heights[at(n, x, z)] = 0.5 * z + 2.0 * std::abs(x - 24) + 10.0;
    const FlowRouting r = routeFlow(heights, n, n, 1.0);
    const std::vector<double> d8 = drainageArea(r, 1.0), mfd = multipleFlowArea(r, 1.0);
    double mouth = 0.0;
    for (int x = 20; x <= 28; ++x) mouth += mfd[at(n, x, 0)];
    EXPECT_GT(mouth, 0.9 * d8[at(n, 24, 0)]);
    EXPECT_LE(mouth, d8[at(n, 24, 0)] * (1.0 + 1e-12));
    EXPECT_GT(mfd[at(n, 24, 1)], 0.9 * d8[at(n, 24, 1)]);
}
