// SPDX-License-Identifier: MIT
// FCL calls in time-limited child processes (FCL 0.7 can abort, throw or loop), the verdicts on
// their answers, and the shrinking of a disagreement to a smaller case that still shows it.
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <limits>

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/continuous_collision.h>
#include <fcl/narrowphase/distance.h>

#include "campaign.hpp"

namespace kairos::fcl_check::campaign {

Answer run_fcl(const Case& c, const Settings& s) {
    Answer out;
    try {
        const auto ga = make_geometry(c.a), gb = make_geometry(c.b);
        switch (s.query) {
            case Query::Distance: {
                const fcl::DistanceRequestd request = distance_request(s);
                fcl::DistanceResultd result;
                fcl::distance(ga.get(), make_transform(c.a0), gb.get(), make_transform(c.b0), request, result);
                out.value = result.min_distance;
                if (result.min_distance == std::numeric_limits<double>::max()) {
                    out.status = Unsupported;
                    std::snprintf(out.message, sizeof out.message, "no distance function for this pair");
                }
                for (int k = 0; k < 3; ++k) {
                    out.points[k] = result.nearest_points[0][k];
                    out.points[3 + k] = result.nearest_points[1][k];
                }
                break;
            }
            case Query::Collide: {
                const fcl::CollisionRequestd request = collision_request(s);
                fcl::CollisionResultd result;
                fcl::collide(ga.get(), make_transform(c.a0), gb.get(), make_transform(c.b0), request, result);
                out.hit = result.isCollision() ? 1 : 0;
                break;
            }
            case Query::Continuous: {
                const fcl::ContinuousCollisionRequestd request = continuous_request(s, c);
                fcl::ContinuousCollisionResultd result;
                const double returned =
                    fcl::continuousCollide(ga.get(), make_transform(c.a0), make_transform(c.a1), gb.get(),
                                           make_transform(c.b0), make_transform(c.b1), request, result);
                out.hit = result.is_collide ? 1 : 0;
                out.value = result.time_of_contact;
                if (returned < 0) {
                    out.status = Unsupported;
                    std::snprintf(out.message, sizeof out.message, "continuousCollide returned %g (no algorithm for the pair)",
                                  returned);
                }
                break;
            }
        }
    } catch (const std::exception& e) {
        out.status = Threw;
        std::snprintf(out.message, sizeof out.message, "%s", e.what());
    } catch (...) {
        out.status = Threw;
        std::snprintf(out.message, sizeof out.message, "a non-standard exception");
    }
    return out;
}

std::vector<Answer> run_guarded(const std::vector<Case>& cases, const Settings& s, size_t batch,
                                const std::function<void(size_t)>& progress) {
    std::vector<Answer> out(cases.size());
    size_t next = 0;
    batch = std::max<size_t>(batch, 1);
    while (next < cases.size()) {
        const size_t end = std::min(cases.size(), next + batch);
        int fd[2];
        if (pipe(fd) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
        std::fflush(nullptr);
        const pid_t pid = fork();
        if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
        if (pid == 0) {
            close(fd[0]);
            // No core files from FCL's aborts; its warnings would garble the parent's output.
            const rlimit no_core{0, 0};
            setrlimit(RLIMIT_CORE, &no_core);
            if (s.quiet_children) {
                const int null = open("/dev/null", O_WRONLY);
                if (null >= 0) dup2(null, STDERR_FILENO), dup2(null, STDOUT_FILENO);
            }
            signal(SIGALRM, SIG_DFL);
            for (size_t i = next; i < end; ++i) {
                alarm(s.timeout_seconds);
                const Answer a = run_fcl(cases[i], s);
                alarm(0);
                if (write(fd[1], &a, sizeof a) != ssize_t(sizeof a)) _exit(3);
            }
            _exit(0);
        }
        close(fd[1]);
        Answer a;
        size_t got = 0;
        for (;;) {
            const ssize_t n = read(fd[0], reinterpret_cast<char*>(&a) + got, sizeof a - got);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) break;
            got += size_t(n);
            if (got == sizeof a) {
                out[next++] = a;
                got = 0;
            }
        }
        close(fd[0]);
        int status = 0;
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
        if (next < end) {
            // The child died on cases[next].
            Answer& dead = out[next++];
            dead = Answer{};
            if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM) {
                dead.status = TimedOut;
                std::snprintf(dead.message, sizeof dead.message, "no answer within %u s", s.timeout_seconds);
            } else {
                dead.status = Crashed;
                if (WIFSIGNALED(status))
                    std::snprintf(dead.message, sizeof dead.message, "signal %d (%s)", WTERMSIG(status),
                                  strsignal(WTERMSIG(status)));
                else
                    std::snprintf(dead.message, sizeof dead.message, "exit status %d", WEXITSTATUS(status));
            }
        }
        if (progress) progress(next);
    }
    return out;
}

std::vector<Verdict> judge(const Case& c, const Settings& s, const Answer& a, const Reference* reference) {
    if (a.status != Answered) return {};
    const auto ga = make_geometry(c.a), gb = make_geometry(c.b);
    if (s.query == Query::Continuous) {
        fcl::ContinuousCollisionResultd result;
        result.is_collide = a.hit != 0;
        result.time_of_contact = a.value;
        return {check_continuous(*ga, make_transform(c.a0), make_transform(c.a1), *gb, make_transform(c.b0),
                                 make_transform(c.b1), continuous_request(s, c), result, s.tolerance)};
    }
    std::unique_ptr<Reference> own;
    if (!reference) {
        own = std::make_unique<Reference>(*ga, make_transform(c.a0), *gb, make_transform(c.b0));
        reference = own.get();
    }
    if (s.query == Query::Distance) {
        fcl::DistanceResultd result;
        result.min_distance = a.value;
        result.nearest_points[0] = fcl::Vector3d(a.points[0], a.points[1], a.points[2]);
        result.nearest_points[1] = fcl::Vector3d(a.points[3], a.points[4], a.points[5]);
        const fcl::DistanceRequestd request = distance_request(s);
        return {reference->check_distance(request, result, s.tolerance),
                reference->check_nearest_points(request, result, s.tolerance)};
    }
    fcl::CollisionResultd result;
    if (a.hit) result.addContact(fcl::Contactd());
    return {reference->check_collision(collision_request(s), result, s.tolerance)};
}

namespace {

const char* status_word(int32_t status) {
    switch (status) {
        case Threw:
            return "exception";
        case Crashed:
            return "crash";
        case TimedOut:
            return "timeout";
        default:
            return "";
    }
}

// FCL's relative error on `what` in this answer: infinite for a crash of that kind, -1 when the
// answer does not show `what`.
double shown(const Case& c, const Answer& a, const std::vector<Verdict>& verdicts, const std::string& what) {
    if (a.status != Answered)
        return a.status != Unsupported && what == status_word(a.status) ? std::numeric_limits<double>::infinity() : -1;
    for (const Verdict& v : verdicts)
        if (v.outcome == Outcome::FclOff && v.quantity == what) return relative_error(v, c);
    return -1;
}

double round_to(double v, int digits) {
    if (v == 0 || !std::isfinite(v)) return v;
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return std::strtod(buf, nullptr);
}

void normalise(std::array<double, 4>& q) {
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(n > 0)) {
        q = {1, 0, 0, 0};
        return;
    }
    for (double& x : q) x /= n;
}

bool rebuild(ShapeSpec& s, const std::vector<Point>& points) {
    std::vector<Point> v;
    std::vector<std::array<int, 3>> t;
    if (!build_hull(points, v, t)) return false;
    s.vertices = std::move(v);
    s.triangles = std::move(t);
    return true;
}

bool sizes_ok(const ShapeSpec& s) {
    const int n = s.kind == Kind::Sphere ? 1 : (s.kind == Kind::Box || s.kind == Kind::Ellipsoid) ? 3
                                             : s.kind == Kind::Convex                             ? 0
                                                                                                  : 2;
    for (int i = 0; i < n; ++i)
        if (!(s.size[size_t(i)] > 0) || !std::isfinite(s.size[size_t(i)])) return false;
    return s.kind != Kind::Convex || s.vertices.size() >= 4;
}

// The case with every number rounded to `digits` significant digits (hulls rebuilt); false
// when that leaves no valid case.
bool rounded(Case& c, int digits) {
    for (ShapeSpec* s : {&c.a, &c.b}) {
        for (double& x : s->size) x = round_to(x, digits);
        if (s->kind == Kind::Convex) {
            std::vector<Point> p = s->vertices;
            for (Point& v : p)
                for (double& x : v) x = round_to(x, digits);
            if (!rebuild(*s, p)) return false;
        }
        if (!sizes_ok(*s)) return false;
    }
    for (PoseSpec* p : {&c.a0, &c.b0, &c.a1, &c.b1}) {
        for (double& x : p->p) x = round_to(x, digits);
        for (double& x : p->q) x = round_to(x, digits);
        normalise(p->q);
    }
    return true;
}

}  // namespace

double relative_error(const Verdict& v, const Case& c) {
    if (v.quantity == "time of contact") return v.error;
    const double size = std::max(shape_radius(c.a), shape_radius(c.b));
    return size > 0 ? v.error / size : v.error;
}

std::string disagreement_of(const Case&, const Settings&, const Answer& a, const std::vector<Verdict>& verdicts) {
    if (a.status == Unsupported) return "";
    if (a.status != Answered) return status_word(a.status);
    for (const Verdict& v : verdicts)
        if (v.outcome == Outcome::FclOff) return v.quantity;
    return "";
}

void shift_case(Case& c, Point d) {
    for (PoseSpec* p : {&c.a0, &c.b0, &c.a1, &c.b1})
        for (int k = 0; k < 3; ++k) p->p[size_t(k)] += d[size_t(k)];
}

Case shrink(const Case& original, const Settings& s, const std::string& what) {
    const auto error_of = [&](const Case& k) {
        try {
            const Answer a = run_guarded({k}, s, 1)[0];
            return shown(k, a, judge(k, s, a), what);
        } catch (const std::exception&) {
            return -1.0;  // a case the adapter refuses (e.g. a rounded quaternion that is no rotation)
        }
    };
    // A simpler case must keep the disagreement and at least half of its size: a reproducer of a
    // 50 % error should not shrink to one of 1e-5.
    const double keep = error_of(original) / 2;
    if (!(keep > 0)) return original;
    const auto persists = [&](const Case& k) { return error_of(k) >= keep; };
    Case best = original;
    const auto attempt = [&](const Case& k) {
        if (!persists(k)) return false;
        best = k;
        return true;
    };
    {
        Case k = best;
        shift_case(k, {-best.a0.p[0], -best.a0.p[1], -best.a0.p[2]});
        attempt(k);
    }
    {
        const double size = std::max(shape_radius(best.a), shape_radius(best.b));
        const int e = int(std::lround(std::log2(size)));
        if (e != 0) {
            Case k = best;
            scale_case(k, std::ldexp(1.0, -e));
            attempt(k);
        }
    }
    const auto drop_turns = [&] {
        Case k = best;
        k.a0.q = k.a1.q = {1, 0, 0, 0};
        attempt(k);
        if (!best.screw) {
            k = best;
            k.b0.q = k.b1.q = {1, 0, 0, 0};
            attempt(k);
        }
    };
    drop_turns();
    const auto round_all = [&] {
        for (int digits = 1; digits <= 8; ++digits) {
            Case k = best;
            if (rounded(k, digits) && attempt(k)) break;
        }
    };
    round_all();
    // Fewer hull vertices, one at a time, while the disagreement stays.
    int tries = 0;
    for (ShapeSpec Case::*member : {&Case::a, &Case::b}) {
        if ((best.*member).kind != Kind::Convex) continue;
        for (size_t i = 0; i < (best.*member).vertices.size() && (best.*member).vertices.size() > 4 && tries < 300;) {
            ++tries;
            Case k = best;
            std::vector<Point> p = (best.*member).vertices;
            p.erase(p.begin() + long(i));
            if (rebuild(k.*member, p) && attempt(k)) continue;
            ++i;
        }
    }
    round_all();
    return best;
}

}  // namespace kairos::fcl_check::campaign
