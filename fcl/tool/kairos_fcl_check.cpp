// SPDX-License-Identifier: MIT
// kairos-fcl-check: runs campaigns of FCL queries (distance, collide, continuous) over shape
// kinds, sizes and placements, each FCL call in a time-limited child process, judges every answer
// against Kairos, shrinks each kind of disagreement to a small case and writes it as a GoogleTest
// reproducer in FCL's style, and prints a summary table. Exit status 0 when FCL agreed everywhere,
// 1 when it did not (a disagreement, crash, exception or timeout), 2 on bad usage.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fcl/config.h>

#include "campaign.hpp"

using namespace kairos::fcl_check;
using namespace kairos::fcl_check::campaign;

namespace {

struct Options {
    std::vector<Query> queries{Query::Distance};
    std::vector<Solver> solvers{Solver::Libccd, Solver::Indep};
    std::vector<Ccd> ccds{Ccd::Advancement};
    std::vector<std::string> families = family_names();
    uint64_t seed = 1;
    uint64_t count = 10000;
    double tolerance = 1e-6;
    double gross = 1e-3;
    double distance_tolerance = 1e-6;
    unsigned timeout = 5;
    std::string out = "fcl-findings";
    int max_reproducers = 24;
    bool shrink = true;
    std::string markdown, csv;
    bool progress = true;
    bool verbose = false;
    std::string command_line;
};

void usage(FILE* f) {
    std::fprintf(f,
                 "usage: kairos-fcl-check [options]\n"
                 "Checks FCL's answers against Kairos and writes reproducers of FCL's wrong answers.\n\n"
                 "  --query LIST          distance, collide, continuous, or all (default distance)\n"
                 "  --solver LIST         libccd, indep (GST_LIBCCD, GST_INDEP; default both)\n"
                 "  --ccd LIST            continuous solvers: advancement, naive (default advancement)\n"
                 "  --families LIST       case families (default all; --list-families names them)\n"
                 "  --seed N              campaign seed (default 1)\n"
                 "  --count N             cases per query, each run once per solver (default 10000)\n"
                 "  --tolerance REL       band a right answer lies in, relative to the shapes' size (default 1e-6),\n"
                 "                        on top of FCL's own tolerances\n"
                 "  --gross REL           the table's \"gross\" column counts errors above REL times the shapes' size\n"
                 "                        (times of contact: above REL of the step; default 1e-3)\n"
                 "  --distance-tolerance T  FCL's DistanceRequest::distance_tolerance (default 1e-6, FCL's default)\n"
                 "  --timeout S           seconds an FCL call may take before it counts as a hang (default 5)\n"
                 "  --out DIR             directory for reproducers and their README.md (default fcl-findings)\n"
                 "  --max-reproducers N   reproducers to write: the worst case of each kind of disagreement (query,\n"
                 "                        solver, what FCL got wrong, shape kinds), largest relative error first (default 24)\n"
                 "  --no-shrink           write the disagreements as found\n"
                 "  --markdown FILE       also write the tables as Markdown\n"
                 "  --csv FILE            every disagreement, one line each\n"
                 "  --no-progress         no progress bar (there is none unless stderr is a terminal)\n"
                 "  --verbose             print each disagreement; keep FCL's own messages\n"
                 "  --list-families       print the case families and exit\n");
}

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

bool parse(int argc, char** argv, Options& o) {
    for (int i = 0; i < argc; ++i) o.command_line += (i ? " " : "") + std::string(i ? argv[i] : "kairos-fcl-check");
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
            return argv[++i];
        };
        if (a == "--help" || a == "-h") {
            usage(stdout);
            std::exit(0);
        } else if (a == "--list-families") {
            for (const std::string& f : family_names()) std::printf("%s\n", f.c_str());
            std::exit(0);
        } else if (a == "--query") {
            o.queries.clear();
            for (const std::string& q : split(value())) {
                if (q == "distance" || q == "all") o.queries.push_back(Query::Distance);
                if (q == "collide" || q == "all") o.queries.push_back(Query::Collide);
                if (q == "continuous" || q == "all") o.queries.push_back(Query::Continuous);
                if (q != "distance" && q != "collide" && q != "continuous" && q != "all")
                    throw std::invalid_argument("unknown query '" + q + "'");
            }
        } else if (a == "--solver") {
            o.solvers.clear();
            for (const std::string& s : split(value())) {
                if (s == "libccd" || s == "GST_LIBCCD")
                    o.solvers.push_back(Solver::Libccd);
                else if (s == "indep" || s == "GST_INDEP")
                    o.solvers.push_back(Solver::Indep);
                else
                    throw std::invalid_argument("unknown solver '" + s + "'");
            }
        } else if (a == "--ccd") {
            o.ccds.clear();
            for (const std::string& s : split(value())) {
                if (s == "advancement" || s == "ca")
                    o.ccds.push_back(Ccd::Advancement);
                else if (s == "naive")
                    o.ccds.push_back(Ccd::Naive);
                else
                    throw std::invalid_argument("unknown continuous solver '" + s + "'");
            }
        } else if (a == "--families") {
            o.families = split(value());
            for (const std::string& f : o.families)
                if (std::find(family_names().begin(), family_names().end(), f) == family_names().end())
                    throw std::invalid_argument("unknown family '" + f + "'");
        } else if (a == "--seed") {
            o.seed = std::stoull(value());
        } else if (a == "--count") {
            o.count = std::stoull(value());
        } else if (a == "--tolerance") {
            o.tolerance = std::stod(value());
        } else if (a == "--gross") {
            o.gross = std::stod(value());
        } else if (a == "--distance-tolerance") {
            o.distance_tolerance = std::stod(value());
        } else if (a == "--timeout") {
            o.timeout = unsigned(std::stoul(value()));
        } else if (a == "--out") {
            o.out = value();
        } else if (a == "--max-reproducers") {
            o.max_reproducers = std::stoi(value());
        } else if (a == "--no-shrink") {
            o.shrink = false;
        } else if (a == "--markdown") {
            o.markdown = value();
        } else if (a == "--csv") {
            o.csv = value();
        } else if (a == "--no-progress") {
            o.progress = false;
        } else if (a == "--verbose") {
            o.verbose = true;
        } else {
            throw std::invalid_argument("unknown option '" + a + "'");
        }
    }
    if (o.queries.empty() || o.solvers.empty() || o.ccds.empty() || o.families.empty())
        throw std::invalid_argument("empty list");
    if (o.timeout == 0) throw std::invalid_argument("--timeout must be at least 1");
    return true;
}

// One row of the table: a quantity asked of one solver.
struct Row {
    std::string quantity, solver;
    uint64_t cases = 0, agree = 0, off = 0, gross = 0, not_judged = 0, unsupported = 0, crashes = 0, threw = 0,
             timeouts = 0;
    double worst = 0, worst_relative = 0;
    uint64_t worst_case = 0;
    std::map<std::string, std::pair<uint64_t, uint64_t>> by_family;  // off, cases
    std::map<std::string, std::pair<uint64_t, uint64_t>> by_pair;
    std::string label() const { return quantity + " " + solver; }
};

struct Finding {
    Case c;
    Settings s;
    std::string what;
    double relative_error = 0;  // error / size; infinite for a crash, exception or timeout
};

std::string pair_name(const Case& c) {
    std::string a = kind_name(c.a.kind), b = kind_name(c.b.kind);
    if (b < a) std::swap(a, b);
    return a + "/" + b;
}

std::string quantity_label(const std::string& quantity, const Settings& s) {
    if (s.query != Query::Continuous) return quantity;
    return quantity + (s.ccd == Ccd::Advancement ? " (CA)" : " (naive)");
}

std::string g3(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

std::string table(const std::vector<Row>& rows, bool markdown) {
    std::ostringstream o;
    const char* head[] = {"query",      "solver",      "cases",   "agree",      "FCL off",  "gross",      "not judged",
                          "unsupported", "crashes", "exceptions", "timeouts", "worst error", "worst relative"};
    std::vector<std::vector<std::string>> cells;
    for (const Row& r : rows)
        cells.push_back({r.quantity, r.solver, std::to_string(r.cases), std::to_string(r.agree), std::to_string(r.off),
                         std::to_string(r.gross), std::to_string(r.not_judged), std::to_string(r.unsupported), std::to_string(r.crashes), std::to_string(r.threw),
                         std::to_string(r.timeouts), r.off ? g3(r.worst) : "-", r.off ? g3(r.worst_relative) : "-"});
    if (markdown) {
        o << "|";
        for (const char* h : head) o << " " << h << " |";
        o << "\n|";
        for (size_t i = 0; i < std::size(head); ++i) o << (i < 2 ? "---|" : "---:|");
        o << "\n";
        for (const auto& row : cells) {
            o << "|";
            for (const auto& c : row) o << " " << c << " |";
            o << "\n";
        }
        return o.str();
    }
    std::vector<size_t> w(std::size(head));
    for (size_t i = 0; i < w.size(); ++i) w[i] = std::strlen(head[i]);
    for (const auto& row : cells)
        for (size_t i = 0; i < w.size(); ++i) w[i] = std::max(w[i], row[i].size());
    const auto line = [&](const std::vector<std::string>& row) {
        for (size_t i = 0; i < w.size(); ++i) {
            const std::string pad(w[i] - row[i].size(), ' ');
            o << (i ? "  " : "") << (i < 2 ? row[i] + pad : pad + row[i]);
        }
        o << "\n";
    };
    line(std::vector<std::string>(std::begin(head), std::end(head)));
    for (const auto& row : cells) line(row);
    return o.str();
}

// Disagreements per family or shape pair: one column per row of the main table.
std::string breakdown(const std::vector<Row>& rows, bool by_family, size_t limit) {
    std::set<std::string> keys;
    std::map<std::string, uint64_t> total;
    for (const Row& r : rows)
        for (const auto& [k, v] : by_family ? r.by_family : r.by_pair) keys.insert(k), total[k] += v.first;
    std::vector<std::string> order(keys.begin(), keys.end());
    if (!by_family)
        std::stable_sort(order.begin(), order.end(), [&](const auto& a, const auto& b) { return total[a] > total[b]; });
    if (order.size() > limit) order.resize(limit);
    std::ostringstream o;
    o << "| " << (by_family ? "family" : "shapes") << " |";
    for (const Row& r : rows) o << " " << r.label() << " |";
    o << "\n|---|";
    for (size_t i = 0; i < rows.size(); ++i) o << "---:|";
    o << "\n";
    for (const std::string& k : order) {
        o << "| " << k << " |";
        for (const Row& r : rows) {
            const auto& m = by_family ? r.by_family : r.by_pair;
            const auto it = m.find(k);
            o << " " << (it == m.end() ? "-" : std::to_string(it->second.first) + " / " + std::to_string(it->second.second))
              << " |";
        }
        o << "\n";
    }
    return o.str();
}

class Progress {
public:
    Progress(bool on, uint64_t total) : on_(on && isatty(STDERR_FILENO)), total_(total) {}
    void update(const std::string& what, uint64_t done, uint64_t off, uint64_t dead) {
        if (!on_) return;
        const int width = 30;
        const int fill = total_ ? int(double(width) * double(done) / double(total_)) : width;
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        std::fprintf(stderr, "\r%-28s [%s%s] %3d%% %llu/%llu  FCL off %llu  crashes %llu  %.0fs ", what.c_str(),
                     std::string(size_t(fill), '#').c_str(), std::string(size_t(width - fill), '.').c_str(),
                     total_ ? int(100.0 * double(done) / double(total_)) : 100, (unsigned long long)done,
                     (unsigned long long)total_, (unsigned long long)off, (unsigned long long)dead, s);
        std::fflush(stderr);
    }
    void done() {
        if (on_) std::fprintf(stderr, "\n");
    }

private:
    bool on_;
    uint64_t total_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

int check(const Options& o) {
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Row> rows;
    std::map<std::string, size_t> row_index;
    const auto row = [&](const std::string& quantity, Solver solver) -> Row& {
        const std::string key = quantity + "|" + solver_name(solver);
        auto it = row_index.find(key);
        if (it == row_index.end()) {
            it = row_index.emplace(key, rows.size()).first;
            Row r;
            r.quantity = quantity;
            r.solver = solver_name(solver);
            rows.push_back(std::move(r));
        }
        return rows[it->second];
    };
    std::map<std::string, Finding> worst_of;  // by kind of disagreement
    std::ofstream csv;
    if (!o.csv.empty()) {
        csv.open(o.csv);
        csv << "query,solver,case,family,shape_a,shape_b,what,fcl,kairos,error,detail\n";
    }

    uint64_t total_work = 0;
    for (Query q : o.queries) total_work += o.count * (q == Query::Continuous ? o.ccds.size() : 1);
    Progress progress(o.progress, total_work * o.solvers.size());
    uint64_t done_work = 0, off_total = 0, dead_total = 0;
    bool all_agree = true;
    constexpr size_t kChunk = 512;

    for (Query query : o.queries) {
        const std::vector<Ccd> ccds = query == Query::Continuous ? o.ccds : std::vector<Ccd>{Ccd::Advancement};
        for (Ccd ccd : ccds) {
            std::vector<Settings> settings;
            for (Solver solver : o.solvers) {
                Settings s;
                s.query = query;
                s.solver = solver;
                s.ccd = ccd;
                s.distance_tolerance = o.distance_tolerance;
                s.tolerance.relative = o.tolerance;
                s.timeout_seconds = o.timeout;
                s.quiet_children = !o.verbose;
                settings.push_back(s);
            }
            // Rows in table order: every quantity of this query for each solver.
            const std::vector<std::string> quantities =
                query == Query::Distance  ? std::vector<std::string>{"distance", "nearest points"}
                : query == Query::Collide ? std::vector<std::string>{"collision"}
                                          : std::vector<std::string>{"time of contact"};
            for (const std::string& qn : quantities)
                for (const Settings& s : settings) row(quantity_label(qn, s), s.solver);
            const std::string what_label = std::string(query_name(query)) +
                                           (query == Query::Continuous ? (ccd == Ccd::Advancement ? " (CA)" : " (naive)") : "");

            for (uint64_t start = 0; start < o.count; start += kChunk) {
                const uint64_t end = std::min<uint64_t>(o.count, start + kChunk);
                std::vector<Case> cases;
                cases.reserve(size_t(end - start));
                for (uint64_t id = start; id < end; ++id) cases.push_back(generate(o.seed, id, query, o.families));
                std::vector<std::vector<Answer>> answers;
                for (const Settings& s : settings) {
                    const uint64_t before = done_work;
                    answers.push_back(run_guarded(cases, s, kChunk, [&](size_t n) {
                        progress.update(what_label, before + n, off_total, dead_total);
                    }));
                    done_work += cases.size();
                }
                for (size_t i = 0; i < cases.size(); ++i) {
                    const Case& c = cases[i];
                    std::optional<Reference> ref;
                    if (query != Query::Continuous)
                        ref.emplace(*make_geometry(c.a), make_transform(c.a0), *make_geometry(c.b), make_transform(c.b0));
                    for (size_t k = 0; k < settings.size(); ++k) {
                        const Settings& s = settings[k];
                        const Answer& a = answers[k][i];
                        const std::vector<Verdict> verdicts = judge(c, s, a, ref ? &*ref : nullptr);
                        Row& primary = row(quantity_label(quantities[0], s), s.solver);
                        if (a.status == Unsupported) {
                            for (const std::string& qn : quantities) {
                                Row& r = row(quantity_label(qn, s), s.solver);
                                ++r.cases, ++r.unsupported;
                            }
                        } else if (a.status != Answered) {
                            if (csv.is_open()) {
                                std::string message = a.message;
                                std::replace(message.begin(), message.end(), ',', ';');
                                csv << query_name(query)
                                    << (query == Query::Continuous ? (ccd == Ccd::Advancement ? "-ca" : "-naive") : "")
                                    << "," << solver_name(s.solver) << "," << c.id << "," << c.family << ","
                                    << kind_name(c.a.kind) << "," << kind_name(c.b.kind) << ","
                                    << disagreement_of(c, s, a, {}) << ",,,," << message << "\n";
                            }
                            ++primary.cases;
                            (a.status == TimedOut ? primary.timeouts : a.status == Threw ? primary.threw : primary.crashes)++;
                            ++primary.by_family[c.family].first, ++primary.by_family[c.family].second;
                            ++primary.by_pair[pair_name(c)].first, ++primary.by_pair[pair_name(c)].second;
                            for (size_t qi = 1; qi < quantities.size(); ++qi) ++row(quantity_label(quantities[qi], s), s.solver).cases;
                            ++dead_total;
                        }
                        for (const Verdict& v : verdicts) {
                            Row& r = row(quantity_label(v.quantity, s), s.solver);
                            ++r.cases;
                            auto& fam = r.by_family[c.family];
                            auto& pair = r.by_pair[pair_name(c)];
                            ++fam.second, ++pair.second;
                            if (v.outcome == Outcome::Agree) ++r.agree;
                            if (v.outcome == Outcome::NotJudged) ++r.not_judged;
                            if (v.outcome != Outcome::FclOff) continue;
                            ++r.off, ++fam.first, ++pair.first, ++off_total;
                            const double rel = relative_error(v, c);
                            if (rel > o.gross) ++r.gross;
                            if (v.error > r.worst) r.worst = v.error, r.worst_case = c.id;
                            r.worst_relative = std::max(r.worst_relative, rel);
                            if (csv.is_open()) {
                                std::string detail = v.detail;
                                std::replace(detail.begin(), detail.end(), ',', ';');
                                char buf[160];
                                std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.6g", v.fcl, v.kairos, v.error);
                                csv << query_name(query) << (query == Query::Continuous ? (ccd == Ccd::Advancement ? "-ca" : "-naive") : "")
                                    << "," << solver_name(s.solver) << "," << c.id << "," << c.family << ","
                                    << kind_name(c.a.kind) << "," << kind_name(c.b.kind) << "," << v.quantity << "," << buf
                                    << "," << detail << "\n";
                            }
                            if (o.verbose) {
                                progress.done();
                                std::printf("case %llu (%s, %s/%s) %s: %s\n", (unsigned long long)c.id, c.family.c_str(),
                                            kind_name(c.a.kind), kind_name(c.b.kind), solver_name(s.solver),
                                            to_string(v).c_str());
                            }
                        }
                        const std::string what = disagreement_of(c, s, a, verdicts);
                        if (what.empty()) continue;
                        all_agree = false;
                        double rel = std::numeric_limits<double>::infinity();
                        for (const Verdict& v : verdicts)
                            if (v.quantity == what) rel = relative_error(v, c);
                        const std::string sig = what_label + "|" + what + "|" + solver_name(s.solver) + "|" +
                                                c.family + "|" + kind_name(c.a.kind) + "|" + kind_name(c.b.kind);
                        const auto it = worst_of.find(sig);
                        if (it == worst_of.end() || rel > it->second.relative_error) worst_of[sig] = {c, s, what, rel};
                    }
                }
                progress.update(what_label, done_work, off_total, dead_total);
            }
        }
    }
    progress.done();
    const double campaign_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    // Reproducers: the worst case of each kind of disagreement (shape kinds within a group of
    // query, what FCL got wrong, solver and family), taken in turns from the groups so that one
    // frequent cause does not fill the quota; within a turn, the largest relative error first.
    std::map<std::string, std::vector<Finding>> groups;
    for (auto& [sig, f] : worst_of) groups[sig.substr(0, sig.rfind('|', sig.rfind('|') - 1))].push_back(std::move(f));
    std::vector<std::vector<Finding>*> order;
    for (auto& [key, list] : groups) {
        std::stable_sort(list.begin(), list.end(),
                         [](const Finding& a, const Finding& b) { return a.relative_error > b.relative_error; });
        order.push_back(&list);
    }
    std::stable_sort(order.begin(), order.end(), [](const auto* a, const auto* b) {
        return a->front().relative_error > b->front().relative_error;
    });
    std::vector<Finding> findings;
    for (size_t turn = 0; findings.size() < size_t(std::max(0, o.max_reproducers)); ++turn) {
        bool any = false;
        for (auto* list : order)
            if (turn < list->size() && findings.size() < size_t(std::max(0, o.max_reproducers)))
                findings.push_back((*list)[turn]), any = true;
        if (!any) break;
    }
    struct Written {
        Finding f;
        Reproducer r;
    };
    std::vector<Written> written;
    if (!findings.empty()) {
        std::filesystem::create_directories(o.out);
        for (size_t i = 0; i < findings.size(); ++i) {
            const Finding& f = findings[i];
            if (o.progress && isatty(STDERR_FILENO))
                std::fprintf(stderr, "\rshrinking and writing reproducer %zu/%zu ", i + 1, findings.size());
            Case c = o.shrink ? shrink(f.c, f.s, f.what) : f.c;
            Reproducer r = write_reproducer(c, f.s, f.what, o.seed, o.shrink);
            if (!r.fails && o.shrink) {
                c = f.c;
                r = write_reproducer(c, f.s, f.what, o.seed, false);
            }
            std::ofstream(std::filesystem::path(o.out) / r.file_name) << r.source;
            written.push_back({{c, f.s, f.what, f.relative_error}, r});
        }
        if (o.progress && isatty(STDERR_FILENO)) std::fprintf(stderr, "\n");
        std::ofstream readme(std::filesystem::path(o.out) / "README.md");
        readme << "# FCL's wrong answers found by kairos-fcl-check\n\n"
               << "Written by `" << o.command_line << "` (Kairos "
               << kairos_version() / 10000 << "." << kairos_version() / 100 % 100 << "." << kairos_version() % 100
               << ", FCL " << FCL_VERSION << "): the worst case of each kind of disagreement (query, solver, what FCL "
               << "gets wrong, family, shape kinds), taken in turns from each family's group, largest error first"
               << (o.shrink ? ", shrunk" : "") << ". Each file is one "
               << "self-contained GoogleTest case using FCL's API only, with the expected value from Kairos and a "
               << "tolerance; it fails on the FCL named. Build one with\n\n"
               << "```sh\ng++ $(pkg-config --cflags fcl) -std=c++17 FILE.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread\n```\n\n"
               << "See docs/fcl-regression.md for how the expected values are certified.\n\n"
               << "| file | query | solver | shapes | family | what FCL gets wrong | error / size | FCL's answer; expected |\n"
               << "|---|---|---|---|---|---|---:|---|\n";
        for (const Written& w : written) {
            std::string q = query_name(w.f.s.query);
            if (w.f.s.query == Query::Continuous)
                q += std::string(w.f.s.ccd == Ccd::Advancement ? " (CA" : " (naive") +
                     (w.f.c.screw ? ", CCDM_SCREW)" : ", CCDM_TRANS)");
            readme << "| [" << w.r.file_name << "](" << w.r.file_name << ") | " << q << " | "
                   << solver_name(w.f.s.solver) << " | " << kind_name(w.f.c.a.kind) << "/" << kind_name(w.f.c.b.kind)
                   << " | " << w.f.c.family << " | " << w.f.what << " | "
                   << (std::isnan(w.r.relative_error) ? std::string("-") : g3(w.r.relative_error)) << " | " << w.r.summary
                   << (w.r.fails ? "" : " (the written assertions pass: not reproduced)") << " |\n";
        }
    }

    const double total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::string plain = table(rows, false);
    std::printf("%s", plain.c_str());
    std::printf("\nseed %llu, %llu cases per query, families %zu; campaign %.1f s, with reproducers %.1f s\n",
                (unsigned long long)o.seed, (unsigned long long)o.count, o.families.size(), campaign_seconds,
                total_seconds);
    for (const Written& w : written)
        std::printf("reproducer %s/%s%s\n", o.out.c_str(), w.r.file_name.c_str(), w.r.fails ? "" : " (does not fail)");
    if (!o.markdown.empty()) {
        std::ofstream md(o.markdown);
        md << "Command: `" << o.command_line << "` (Kairos " << kairos_version() / 10000 << "."
           << kairos_version() / 100 % 100 << "." << kairos_version() % 100 << ", FCL " << FCL_VERSION << "); "
           << "campaign " << g3(campaign_seconds) << " s.\n\n"
           << table(rows, true) << "\nFCL off / cases by family:\n\n"
           << breakdown(rows, true, 100) << "\nFCL off / cases by shape pair (the 15 with most):\n\n"
           << breakdown(rows, false, 15);
    }
    return all_agree ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    try {
        parse(argc, argv, o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "kairos-fcl-check: %s\n\n", e.what());
        usage(stderr);
        return 2;
    }
    try {
        return check(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "\nkairos-fcl-check: %s\n", e.what());
        return 2;
    }
}
