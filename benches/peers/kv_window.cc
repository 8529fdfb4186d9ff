// kv_window: the flow of NDBWSHCCM (eq:BWSHCCM_nd) or NDBWMCM (eq:BWMCM_nd) over a time window
// [t0, t1] enclosed by kv (Kashiwagi's validated-numerics headers), the peer of bwcl's
// `Window::enclose` (src/engines/taylor/window.rs) in benches/peers/run.py.
//
// kv integrates analytic fields. On a window where every switching component keeps the sign
// s = ±1 it has at t0, |x| = s·x, |x|^q = (s·x)^q and |x|^(q−1)·x = s·(s·x)^q are analytic
// (s·x > 0), and the model is written with these substitutions: the same equations, valid on
// the window only: every step is checked to keep the signs (StepCounter), else the run fails.
//
// usage:
//   kv_window <shc|maxwell> <maffine|maffine2|qr_lohner> <B,Γ,κ,σ,n,p> <t0> <t1> <x1,..,xN>
//             [radius=0] [order=16] [reps=0] [min_ms=300] [form=direct|merged]
//
//   parameters: decimals as written, enclosed outward (kv::interval<double>("0.632"));
//   t0, t1, state: exact doubles (hex floats like -0x1.f1c3p-2, or decimals that read back to
//   the intended double, e.g. 17 significant digits); the start box is x ± radius (outward);
//   reps > 0: that many timed runs, else runs until min_ms of wall time have passed (at least
//   one); form=merged writes B·s_Z s_W·|Z|^n·W + Γ·|Z|^n·W as one product (B s s' + Γ)·|Z|^n·W.
//
// output, one "key value..." per line (the same keys as bwcl's window_bwcl example):
//   engine kv <method>, model, order, radius, steps, reps, wall_per_run_s, cpu_per_run_s, and
//   per component "x <i> <lo> <hi>" with the bounds as hex floats (%a: exact); on failure one
//   line "failed <why>" and exit status 1.
//
// build: g++ -O3 -DNDEBUG -DKV_FASTROUND -I $KV_DIR kv_window.cc -o kv_window (needs Boost's
// headers: Debian's libboost-dev).

#include <time.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <kv/ode-maffine.hpp>
#include <kv/ode-maffine2.hpp>
#include <kv/ode-qr-lohner.hpp>

namespace ub = boost::numeric::ublas;
typedef kv::interval<double> itv;

[[noreturn]] static void die(const std::string& why) {
	std::printf("failed %s\n", why.c_str());
	std::exit(1);
}

static std::vector<std::string> split(const std::string& s, char sep) {
	std::vector<std::string> out;
	std::stringstream ss(s);
	std::string item;
	while (std::getline(ss, item, sep)) out.push_back(item);
	return out;
}

// a double written exactly (strtod reads hex floats and rounds decimals correctly)
static double exact_double(const std::string& s) {
	char* end = nullptr;
	double x = std::strtod(s.c_str(), &end);
	if (s.empty() || *end != '\0') die("not a number: '" + s + "'");
	return x;
}

// s·a for s = ±1 (exact)
template <class T> static T signed_(int s, const T& a) { return s > 0 ? a : T(-a); }

// P = (B, Γ, κ, σ, n, p) and the products the fields use, enclosed from the decimals
struct Params {
	itv b, gamma, kappa, sigma, n, p, kappa_c, kps, kcps;
	bool merged = false;
	explicit Params(const std::string& text) {
		std::vector<std::string> v = split(text, ',');
		if (v.size() != 6) die("parameters: want B,Γ,κ,σ,n,p, got '" + text + "'");
		b = itv(v[0]);
		gamma = itv(v[1]);
		kappa = itv(v[2]);
		sigma = itv(v[3]);
		n = itv(v[4]);
		p = itv(v[5]);
		kappa_c = itv(1.) - kappa;
		kps = kappa * p * sigma;
		kcps = kappa_c * p * sigma;
	}
};

// The hysteretic rate of eq:BWHCL in nondimensional form, input u with sign su and Z with sign
// sz on the window:  Ż = u − B |Z|^(n−1) Z |u| − Γ |Z|^n u,  |Z|^(n−1) Z = sz |Z|^n, |u| = su u.
template <class T> static T hysteretic_rate(const Params& q, int sz, int su, const T& z, const T& u) {
	T zn = pow(signed_(sz, z), q.n);  // |Z|^n
	if (q.merged) return u - (q.b * double(sz * su) + q.gamma) * (zn * u);
	return u - q.b * (signed_(sz, zn) * signed_(su, u)) - q.gamma * (zn * u);
}

// NDBWSHCCM (eq:BWSHCCM_nd), state (X, Z, V), signs (sx, sz, sv) on the window:
//   Ẋ = V
//   Ż = V − B |Z|^(n−1) Z |V| − Γ |Z|^n V
//   V̇ = −κ |X|^(p−1) X − κ_c |Z|^(p−1) Z − σ |X|^p V
struct Shc {
	Params q;
	int sx, sz, sv;
	template <class T> ub::vector<T> operator()(const ub::vector<T>& s, const T&) const {
		const T &x = s(0), &z = s(1), &v = s(2);
		T xp = pow(signed_(sx, x), q.p);  // |X|^p
		T zp = pow(signed_(sz, z), q.p);  // |Z|^p
		ub::vector<T> f(3);
		f(0) = v;
		f(1) = hysteretic_rate(q, sz, sv, z, v);
		f(2) = -q.kappa * signed_(sx, xp) - q.kappa_c * signed_(sz, zp) - q.sigma * (xp * v);
		return f;
	}
};

// NDBWMCM (eq:BWMCM_nd), state (R, Y, Z, W), signs (sy, sz, sw) on the window:
//   F_P = −κ |Y|^(p−1) Y − κ_c |Z|^(p−1) Z,   Ṙ = −σ F_P
//   Ẏ = W
//   Ż = W − B |Z|^(n−1) Z |W| − Γ |Z|^n W
//   Ẇ = −Ṙ/σ − κpσ |Y|^(p−1) Ẏ − κ_c pσ |Z|^(p−1) Ż   (−Ṙ/σ written as F_P itself)
struct Maxwell {
	Params q;
	int sy, sz, sw;
	template <class T> ub::vector<T> operator()(const ub::vector<T>& s, const T&) const {
		const T &y = s(1), &z = s(2), &w = s(3);
		T yb = pow(signed_(sy, y), q.p - 1.);  // |Y|^(p−1)
		T zb = pow(signed_(sz, z), q.p - 1.);  // |Z|^(p−1)
		T fp = -q.kappa * (yb * y) - q.kappa_c * (zb * z);
		T dz = hysteretic_rate(q, sz, sw, z, w);
		ub::vector<T> f(4);
		f(0) = -q.sigma * fp;
		f(1) = w;
		f(2) = dz;
		f(3) = fp - q.kps * (yb * w) - q.kcps * (zb * dz);
		return f;
	}
};

// A switching component of the model: its index, name and sign on the window.
struct Switching {
	size_t i;
	const char* name;
	int sign;
};

// Counts kv's steps (one call per accepted step) and checks on each step that every switching
// component keeps its sign: kv's series of the step (Taylor polynomial and type-II remainder,
// in τ = t − start) evaluated over [0, h]. The substituted field is analytic across a kink of
// |·| (there it is the field continued from the other side, not the model's), so without this
// kv would integrate past V = 0 with the wrong field; returning false stops kv (odelong → 3).
struct StepCounter : kv::ode_callback<double> {
	int* steps;
	const std::vector<Switching>* switching;
	std::string* violation;
	bool operator()(const itv& start, const itv& end, const ub::vector<itv>&, const ub::vector<itv>&,
	                const ub::vector<kv::psa<itv> >& series) const override {
		++*steps;
		itv tau(0., (end - start).upper());
		for (const Switching& c : *switching) {
			itv range = eval(series(c.i), tau);  // (a friend of psa, found by ADL)
			if (!(c.sign > 0 ? range.lower() > 0. : range.upper() < 0.)) {
				char buf[200];
				std::snprintf(buf, sizeof buf,
				              "the switching component %s may change sign on the step [%.17g, %.17g] "
				              "(range [%.3e, %.3e]): the window is not a smooth stretch",
				              c.name, start.lower(), end.upper(), range.lower(), range.upper());
				*violation = buf;
				return false;
			}
		}
		return true;
	}
};

// one integration of the window: the enclosure at t1 in x, kv's steps returned
template <class F>
static int integrate(const F& f, const std::string& method, ub::vector<itv>& x, double t0,
                     double t1, const kv::ode_param<double>& prm, const std::vector<Switching>& sw) {
	int steps = 0;
	std::string violation;
	StepCounter count;
	count.steps = &steps;
	count.switching = &sw;
	count.violation = &violation;
	itv end(t1);
	int r = 0;
	try {
		if (method == "maffine") r = kv::odelong_maffine(f, x, itv(t0), end, prm, count);
		else if (method == "maffine2") r = kv::odelong_maffine2(f, x, itv(t0), end, prm, count);
		else if (method == "qr_lohner") r = kv::odelong_qr_lohner(f, x, itv(t0), end, prm, count);
		else die("method: want maffine, maffine2 or qr_lohner, got '" + method + "'");
	} catch (const std::exception& e) {
		die(std::string("kv threw: ") + e.what());
	}
	if (!violation.empty()) die(violation);
	// 2: the end was reached; 1: only [t0, end] with end < t1; 0: no step
	if (r != 2) {
		char buf[160];
		std::snprintf(buf, sizeof buf, "kv returned %d: reached T = %.17g of [%.17g, %.17g]", r,
		              r == 1 ? end.lower() : t0, t0, t1);
		die(buf);
	}
	return steps;
}

static double cpu_seconds() {
	timespec c;
	clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c);
	return c.tv_sec + 1e-9 * c.tv_nsec;
}

struct Options {
	double radius = 0.;
	int order = 16;
	long reps = 0;
	double min_ms = 300.;
	std::string form = "direct";
};

template <class F>
static void run(const F& f, const std::vector<Switching>& sw, const std::string& model,
                const std::string& method, const std::vector<double>& xs, double t0, double t1,
                const Options& o) {
	ub::vector<itv> x0(xs.size());
	for (size_t i = 0; i < xs.size(); i++) x0(i) = itv(xs[i]) + itv(-o.radius, o.radius);
	kv::ode_param<double> prm;
	prm.set_order(o.order);
	ub::vector<itv> x = x0;
	int steps = integrate(f, method, x, t0, t1, prm, sw);
	double c0 = cpu_seconds();
	auto w0 = std::chrono::steady_clock::now();
	long reps = 0;
	double wall;
	while (true) {
		ub::vector<itv> xx = x0;
		integrate(f, method, xx, t0, t1, prm, sw);
		reps++;
		wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
		if (o.reps > 0 ? reps >= o.reps : wall * 1e3 >= o.min_ms) break;
	}
	double cpu = cpu_seconds() - c0;
	std::printf("engine kv %s\n", method.c_str());
	std::printf("model %s\n", model.c_str());
	std::printf("order %d\n", o.order);
	std::printf("radius %a\n", o.radius);
	std::printf("steps %d\n", steps);
	std::printf("reps %ld\n", reps);
	std::printf("wall_per_run_s %.6e\n", wall / reps);
	std::printf("cpu_per_run_s %.6e\n", cpu / reps);
	for (size_t i = 0; i < x.size(); i++) std::printf("x %zu %a %a\n", i, x(i).lower(), x(i).upper());
}

// the switching components (index, name) with their signs over the start box: each must keep
// one on the window
static std::vector<Switching> switching(const std::vector<double>& xs, double radius,
                                        const std::vector<std::pair<size_t, const char*> >& which) {
	std::vector<Switching> out;
	for (const auto& w : which) {
		itv b = itv(xs[w.first]) + itv(-radius, radius);
		if (!(b.lower() > 0. || b.upper() < 0.))
			die(std::string("the switching component ") + w.second +
			    " holds 0 at t0: kv needs a window on which it keeps its sign");
		out.push_back({w.first, w.second, b.lower() > 0. ? 1 : -1});
	}
	return out;
}

int main(int argc, char** argv) {
	if (argc < 7) {
		std::fprintf(stderr,
		             "usage: kv_window <shc|maxwell> <maffine|maffine2|qr_lohner> <B,G,kappa,sigma,n,p> "
		             "<t0> <t1> <x1,..,xN> [radius=0] [order=16] [reps=0] [min_ms=300] [form=direct|merged]\n");
		return 2;
	}
	std::string model = argv[1], method = argv[2];
	Params q(argv[3]);
	double t0 = exact_double(argv[4]), t1 = exact_double(argv[5]);
	std::vector<double> xs;
	for (const std::string& c : split(argv[6], ',')) xs.push_back(exact_double(c));
	Options o;
	for (int a = 7; a < argc; a++) {
		std::string kvp = argv[a];
		size_t eq = kvp.find('=');
		if (eq == std::string::npos) die("option: want key=value, got '" + kvp + "'");
		std::string k = kvp.substr(0, eq), v = kvp.substr(eq + 1);
		if (k == "radius") o.radius = exact_double(v);
		else if (k == "order") o.order = std::atoi(v.c_str());
		else if (k == "reps") o.reps = std::atol(v.c_str());
		else if (k == "min_ms") o.min_ms = exact_double(v);
		else if (k == "form") o.form = v;
		else die("unknown option '" + k + "'");
	}
	if (o.form != "direct" && o.form != "merged") die("form: want direct or merged");
	q.merged = o.form == "merged";
	if (!(t0 < t1)) die("want t0 < t1");
	if (!(o.radius >= 0.) || o.order < 2) die("want radius >= 0 and order >= 2");
	if (model == "shc") {
		if (xs.size() != 3) die("shc: want the state X,Z,V");
		std::vector<Switching> sw = switching(xs, o.radius, {{0, "X"}, {1, "Z"}, {2, "V"}});
		run(Shc{q, sw[0].sign, sw[1].sign, sw[2].sign}, sw, model, method, xs, t0, t1, o);
	} else if (model == "maxwell") {
		if (xs.size() != 4) die("maxwell: want the state R,Y,Z,W");
		std::vector<Switching> sw = switching(xs, o.radius, {{1, "Y"}, {2, "Z"}, {3, "W"}});
		run(Maxwell{q, sw[0].sign, sw[1].sign, sw[2].sign}, sw, model, method, xs, t0, t1, o);
	} else {
		die("model: want shc or maxwell, got '" + model + "'");
	}
	return 0;
}
