// SPDX-License-Identifier: MIT
// Cast benchmark, Bullet's float build (btSubsimplexConvexCast) on the same fixed sets as
// bench_cast; its own program, since the float and double builds of Bullet export the same names.
//   bench_cast_bullet32 [out.csv]   (rows without the header; default: standard output)
#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>
#include <vector>

#include "cast_bench_common.hpp"
#include "cast_peer_bullet.hpp"

using namespace cast_bench;

int main(int argc, char** argv) {
    FILE* out = open_output(argc, argv);
    if (!out) return 2;
    for (const Scenario& sc : kScenarios) {
        const std::vector<Item> set = make_set(sc);
        std::vector<kairos::CastResult> res(set.size());
        std::vector<std::unique_ptr<btConvexShape>> sa, sb;
        for (const Item& x : set) {
            sa.push_back(cast_peer::bullet_shape(x.a.body));
            sb.push_back(cast_peer::bullet_shape(x.b.body));
        }
        auto one = [&](size_t i) {
            res[i] = cast_peer::bullet_cast(*sa[i], *sb[i], set[i].c);
            benchmark::DoNotOptimize(res[i]);
        };
        const Timing ns = time_casts(one, set.size());
        csv_row(out, sc.name, "bullet32", double(MAX_CONVEX_CAST_EPSILON), ns, summarize(set, res, true, false, false));
    }
    if (out != stdout) std::fclose(out);
    return 0;
}
