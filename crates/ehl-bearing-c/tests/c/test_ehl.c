/*
 * C test of the ehl-bearing C interface: builds the dry, fitted-law, trend and characterized
 * elements, evaluates them and compares every number with the Rust library's reference file
 * (crates/ehl-bearing-c/src/reference.rs) to round-off; then the error paths (bad TOML, NULL
 * pointers, NaN inputs, unknown method, cancel) and a timed loop of force-element calls.
 *
 * Usage: test_ehl REPO_ROOT REFERENCE_FILE
 * Environment: EHL_BENCH_CALLS (default 2000): calls in the timed loop.
 * Driven by tests/c_program.rs (cargo test -p ehl-bearing-c).
 */
#define _POSIX_C_SOURCE 200809L
#include "ehl_bearing.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int passed = 0, failed = 0;

#define CHECK(cond, ...)                                                                      \
    do {                                                                                      \
        if (cond) {                                                                           \
            passed++;                                                                         \
        } else {                                                                              \
            failed++;                                                                         \
            fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__);                              \
            fprintf(stderr, __VA_ARGS__);                                                     \
            fprintf(stderr, "\n");                                                            \
        }                                                                                     \
    } while (0)

/* A call that must succeed: on failure print the library's message and stop. */
#define MUST(call)                                                                            \
    do {                                                                                      \
        int st_ = (call);                                                                     \
        if (st_ != EHL_OK) {                                                                  \
            fprintf(stderr, "FATAL %s:%d: %s -> %d: %s\n", __FILE__, __LINE__, #call, st_,    \
                    ehl_last_error());                                                        \
            exit(2);                                                                          \
        }                                                                                     \
    } while (0)

#define REL_TOL 1e-12
#define PI 3.14159265358979323846

/* |a - b| <= REL_TOL * scale, scale = the largest |reference| of the array (round-off). */
static int compare(const char *what, int line, const double *got, const double *want, int n) {
    double scale = 0.0, worst = 0.0;
    int i, bad = -1;
    for (i = 0; i < n; i++)
        if (fabs(want[i]) > scale) scale = fabs(want[i]);
    for (i = 0; i < n; i++) {
        double d = fabs(got[i] - want[i]);
        if (d > worst) worst = d;
        if (!(d <= REL_TOL * scale) && bad < 0) bad = i;
    }
    CHECK(bad < 0, "reference line %d, %s[%d]: C %.17g, Rust %.17g (largest difference %.3g, scale %.3g)",
          line, what, bad, bad >= 0 ? got[bad] : 0.0, bad >= 0 ? want[bad] : 0.0, worst, scale);
    return bad < 0;
}

static char *read_text(const char *path) {
    FILE *f = fopen(path, "rb");
    long n;
    char *buf;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    buf = malloc((size_t)n + 1);
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    if (buf) buf[n] = '\0';
    fclose(f);
    return buf;
}

/* Read n numbers from *p (advanced). */
static int numbers(char **p, double *out, int n) {
    int i;
    for (i = 0; i < n; i++) {
        char *end;
        out[i] = strtod(*p, &end);
        if (end == *p) return 0;
        *p = end;
    }
    return 1;
}

static double now_s(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef struct {
    int events;
    int iteration_started;
    int cancel_at; /* cancel at this event (1-based); 0: never */
} Progress;

static int on_progress(const char *event_json, void *user) {
    Progress *p = (Progress *)user;
    p->events++;
    if (strstr(event_json, "\"iteration_started\"")) p->iteration_started++;
    return p->cancel_at > 0 && p->events >= p->cancel_at;
}

#define NAMES 4
static const char *names[NAMES] = {"dry", "fitted", "trend", "synthetic"};

static int index_of(const char *name) {
    int i;
    for (i = 0; i < NAMES; i++)
        if (strcmp(names[i], name) == 0) return i;
    return -1;
}

int main(int argc, char **argv) {
    char path[4096];
    EhlCase *c = NULL, *c3000 = NULL;
    EhlElement *el[NAMES] = {NULL};
    EhlState *st[NAMES] = {NULL};
    EhlCharacterization *ch = NULL;
    Progress prog = {0, 0, 0};
    char *text, *line, *save = NULL;
    int lineno = 0, evals = 0;

    if (argc < 3) {
        fprintf(stderr, "usage: %s REPO_ROOT REFERENCE_FILE\n", argv[0]);
        return 2;
    }
    printf("ehl-bearing C interface %s\n", ehl_version());

    /* Objects: the same as src/reference.rs builds through the Rust API. */
    snprintf(path, sizeof path, "%s/examples/7006.toml", argv[1]);
    MUST(ehl_case_from_file(path, &c));
    MUST(ehl_case_with_inner_speed_rpm(c, 3000.0, &c3000));
    MUST(ehl_element_hertz(c, &el[0]));
    snprintf(path, sizeof path, "%s/crates/ehl-bearing-py/tests/data/fitted_7006_3000rpm_harmonic.json", argv[1]);
    MUST(ehl_element_from_report_file(c3000, path, &el[1]));
    snprintf(path, sizeof path, "%s/docs/figures/study_7006_quasi_static_trends.json", argv[1]);
    MUST(ehl_element_trend_from_file(path, &el[2]));
    MUST(ehl_characterize(c, "synthetic", on_progress, &prog, &ch));
    MUST(ehl_element_from_characterization(ch, &el[3]));
    CHECK(prog.events > 0 && prog.iteration_started > 0, "progress events: %d", prog.events);
    {
        int i;
        for (i = 0; i < NAMES; i++) MUST(ehl_state_new(&st[i]));
    }
    {
        EhlCaseInfo ci;
        EhlElementInfo ei;
        MUST(ehl_case_info(c, &ci));
        CHECK(ci.ball_count == 11 && fabs(ci.ball_diameter_m - 7e-3) < 1e-15 &&
                  fabs(ci.inner_speed_rad_s - 5000.0 * PI / 30.0) < 1e-9,
              "case info: Z %u, D %g, speed %g", ci.ball_count, ci.ball_diameter_m, ci.inner_speed_rad_s);
        MUST(ehl_element_info(el[1], &ei));
        CHECK(ei.kind == EHL_ELEMENT_FITTED && ei.has_damping == 1 && ei.ball_count == 11,
              "fitted element info: kind %d, damping %d", ei.kind, ei.has_damping);
        MUST(ehl_element_info(el[2], &ei));
        CHECK(ei.kind == EHL_ELEMENT_TREND && ei.has_damping == 0, "trend element info");
        MUST(ehl_element_info(el[0], &ei));
        CHECK(ei.kind == EHL_ELEMENT_DRY && ei.has_damping == 0, "dry element info");
    }

    /* Every number of the reference file. */
    text = read_text(argv[2]);
    if (!text) {
        fprintf(stderr, "FATAL: cannot read %s\n", argv[2]);
        return 2;
    }
    for (line = strtok_r(text, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
        char kind[32], name[32];
        char *p;
        int n = 0, k;
        lineno++;
        if (line[0] == '#') continue;
        if (sscanf(line, "%31s %31s%n", kind, name, &n) != 2) continue;
        p = line + n;
        k = index_of(name);
        if (strcmp(kind, "eval") == 0) {
            double in[13], want[56];
            EhlInput input;
            EhlOutput out;
            CHECK(k >= 0 && numbers(&p, in, 13) && numbers(&p, want, 56), "line %d unreadable", lineno);
            if (k < 0) continue;
            memcpy(input.displacement, in, sizeof input.displacement);
            memcpy(input.velocity, in + 5, sizeof input.velocity);
            input.inner_speed_rad_s = in[10];
            input.outer_speed_rad_s = in[11];
            input.cage_angle_rad = in[12];
            MUST(ehl_evaluate(el[k], st[k], &input, &out));
            compare("reaction", lineno, out.reaction, want, 5);
            compare("stiffness", lineno, out.stiffness, want + 5, 25);
            compare("damping", lineno, out.damping, want + 30, 25);
            compare("operating cage speed", lineno, &out.cage_speed_rad_s, want + 55, 1);
            evals++;
        } else if (strcmp(kind, "cage") == 0) {
            double v[3], got;
            CHECK(k >= 0 && numbers(&p, v, 3), "line %d unreadable", lineno);
            if (k < 0) continue;
            MUST(ehl_element_cage_speed(el[k], v[0], v[1], &got));
            compare("cage speed", lineno, &got, v + 2, 1);
        } else if (strcmp(kind, "equilibrium") == 0) {
            double want[30], q[5], kk[25];
            CHECK(k >= 0 && numbers(&p, want, 30), "line %d unreadable", lineno);
            if (k < 0) continue;
            MUST(ehl_element_equilibrium(el[k], k == 1 ? c3000 : c, q, kk, NULL));
            compare("equilibrium displacement", lineno, q, want, 5);
            compare("equilibrium stiffness", lineno, kk, want + 5, 25);
        } else if (strcmp(kind, "summary") == 0) {
            double want[32];
            EhlCharacterizationSummary s;
            CHECK(numbers(&p, want, 32), "line %d unreadable", lineno);
            MUST(ehl_characterization_summary(ch, &s));
            CHECK(s.converged == (int)want[0] && s.iterations == (unsigned)want[1],
                  "summary converged %d iterations %u", s.converged, s.iterations);
            compare("summary displacement", lineno, s.displacement, want + 2, 5);
            compare("summary stiffness", lineno, s.stiffness, want + 7, 25);
        }
    }
    free(text);
    CHECK(evals == 16, "evaluations compared: %d (16 expected)", evals);

    /* The report round trip: the characterization's JSON as a fitted-law element gives the
       same numbers as the element from the characterization. */
    {
        char *json = NULL;
        EhlElement *again = NULL;
        EhlState *s1 = NULL, *s2 = NULL;
        EhlInput in;
        EhlOutput a, b;
        double q[5];
        MUST(ehl_characterization_json(ch, 0, &json));
        CHECK(strstr(json, "\"contacts\"") != NULL, "report JSON has contacts");
        MUST(ehl_element_from_report_json(c, json, &again));
        ehl_string_free(json);
        MUST(ehl_element_equilibrium(el[3], c, q, NULL, NULL));
        memset(&in, 0, sizeof in);
        memcpy(in.displacement, q, sizeof q);
        in.inner_speed_rad_s = 5000.0 * PI / 30.0;
        MUST(ehl_state_new(&s1));
        MUST(ehl_state_new(&s2));
        MUST(ehl_evaluate(el[3], s1, &in, &a));
        MUST(ehl_evaluate(again, s2, &in, &b));
        compare("report round trip reaction", 0, b.reaction, a.reaction, 5);
        compare("report round trip stiffness", 0, b.stiffness, a.stiffness, 25);
        {
            double loads[22], appr[22];
            size_t count = 0;
            MUST(ehl_state_contacts(s1, loads, appr, 22, &count));
            CHECK(count == 22 && loads[0] > 0.0 && appr[0] > 0.0, "contacts: %zu, load %g", count, loads[0]);
            CHECK(ehl_state_contacts(s1, loads, appr, 3, &count) == EHL_ERR_ARGUMENT, "small capacity refused");
        }
        ehl_state_free(s1);
        ehl_state_free(s2);
        ehl_element_free(again);
    }

    /* Coefficients from an element, and ROSS's table. */
    {
        double speeds[2] = {3000.0, 5000.0};
        char *json = NULL, *csv = NULL;
        MUST(ehl_coefficients(c, speeds, 2, NULL, el[0], NULL, NULL, &json));
        CHECK(strstr(json, "\"stiffness\"") && strstr(json, "\"inner_speed_rpm\":3000"), "coefficients JSON: %.200s", json);
        MUST(ehl_ross_table_csv(json, &csv));
        CHECK(strncmp(csv, "frequency", 9) == 0 || strlen(csv) > 20, "ROSS table: %.100s", csv);
        ehl_string_free(json);
        ehl_string_free(csv);
        CHECK(ehl_coefficients(c, speeds, 0, NULL, el[0], NULL, NULL, &json) == EHL_ERR_ARGUMENT,
              "zero speeds refused");
    }

    /* The embedded law maps' summaries. */
    {
        char *json = NULL;
        MUST(ehl_law_maps_json(&json));
        CHECK(json[0] == '[' && strstr(json, "\"law\":\"quasi-static\"") && strstr(json, "\"law\":\"harmonic\"")
                  && strstr(json, "\"group\":\"m\",\"min\":120.0,\"max\":4000.0,\"nodes\":17"),
              "law maps JSON: %.200s", json);
        ehl_string_free(json);
        CHECK(ehl_law_maps_json(NULL) == EHL_ERR_NULL && strstr(ehl_last_error(), "out_json"),
              "NULL out_json: %s", ehl_last_error());
    }

    /* Error paths: status and message, never a crash. */
    {
        EhlCase *bad = NULL;
        EhlCharacterization *none = NULL;
        EhlInput in;
        EhlOutput out;
        const char *msg;
        int st;

        st = ehl_case_from_toml("this is [ not toml", "bad.toml", &bad);
        msg = ehl_last_error();
        CHECK(st == EHL_ERR_INPUT && bad == NULL && strstr(msg, "bad.toml"), "bad TOML: %d %s", st, msg);
        st = ehl_case_from_toml("[bearing]\nball_count = 0\n", NULL, &bad);
        msg = ehl_last_error();
        CHECK(st == EHL_ERR_INPUT && strlen(msg) > 10, "invalid case: %d %s", st, msg);
        st = ehl_case_from_file("/nonexistent/case.toml", &bad);
        CHECK(st == EHL_ERR_INPUT && strstr(ehl_last_error(), "/nonexistent/case.toml"), "missing file: %s", ehl_last_error());
        st = ehl_case_from_file(NULL, &bad);
        CHECK(st == EHL_ERR_NULL && strstr(ehl_last_error(), "path"), "NULL path: %s", ehl_last_error());
        st = ehl_case_from_toml("x = 1", NULL, NULL);
        CHECK(st == EHL_ERR_NULL && strstr(ehl_last_error(), "out"), "NULL out: %s", ehl_last_error());
        st = ehl_case_with_inner_speed_rpm(c, NAN, &bad);
        CHECK(st == EHL_ERR_ARGUMENT && strstr(ehl_last_error(), "rpm"), "NaN rpm: %s", ehl_last_error());

        memset(&in, 0, sizeof in);
        in.displacement[0] = 2e-5;
        in.inner_speed_rad_s = 500.0;
        st = ehl_evaluate(NULL, NULL, &in, &out);
        CHECK(st == EHL_ERR_NULL && strstr(ehl_last_error(), "element"), "NULL element: %s", ehl_last_error());
        st = ehl_evaluate(el[0], NULL, &in, &out);
        CHECK(st == EHL_ERR_NULL && strstr(ehl_last_error(), "state"), "NULL state: %s", ehl_last_error());
        st = ehl_evaluate(el[0], NULL, NULL, &out);
        CHECK(st == EHL_ERR_NULL, "NULL state and input");
        in.displacement[2] = NAN;
        {
            EhlState *s = NULL;
            MUST(ehl_state_new(&s));
            st = ehl_evaluate(el[0], s, &in, &out);
            msg = ehl_last_error();
            CHECK(st == EHL_ERR_ARGUMENT && strstr(msg, "input->displacement[2]") && strstr(msg, "NaN"),
                  "NaN displacement: %d %s", st, msg);
            in.displacement[2] = 0.0;
            in.cage_angle_rad = INFINITY;
            st = ehl_evaluate(el[0], s, &in, &out);
            CHECK(st == EHL_ERR_ARGUMENT && strstr(ehl_last_error(), "cage_angle_rad"), "inf cage: %s", ehl_last_error());
            in.cage_angle_rad = 0.0;
            st = ehl_evaluate(el[0], s, &in, &out);
            CHECK(st == EHL_OK && ehl_last_error()[0] == '\0' && out.reaction[0] > 0.0,
                  "state usable after errors: %d %s", st, ehl_last_error());
            ehl_state_free(s);
        }
        st = ehl_characterize(c, "magic", NULL, NULL, &none);
        CHECK(st == EHL_ERR_INPUT && strstr(ehl_last_error(), "unknown method") && none == NULL,
              "unknown method: %s", ehl_last_error());
        {
            Progress cancel = {0, 0, 1};
            st = ehl_characterize(c, "synthetic", on_progress, &cancel, &none);
            CHECK(st == EHL_ERR_CANCELLED && none == NULL && cancel.events >= 1, "cancel: %d %s", st, ehl_last_error());
        }
        st = ehl_element_from_report_json(c, "{\"not\": \"a report\"}", &el[0]);
        CHECK(st == EHL_ERR_INPUT && strstr(ehl_last_error(), "report"), "bad report: %s", ehl_last_error());
        st = ehl_element_trend_from_json("[]", &el[0]);
        CHECK(st == EHL_ERR_INPUT, "bad trends: %s", ehl_last_error());
        CHECK(el[0] != NULL, "failed calls leave outputs alone");
        ehl_case_free(NULL);
        ehl_element_free(NULL);
        ehl_state_free(NULL);
        ehl_characterization_free(NULL);
        ehl_string_free(NULL);
    }

    /* Timed loop: one force-element call with warm state (fitted laws with damping, displaced,
       with rates and a turning cage), as the Rust benchmark force_element does. */
    {
        const char *env = getenv("EHL_BENCH_CALLS");
        long calls = env ? atol(env) : 2000, i;
        EhlInput in;
        EhlOutput out;
        EhlState *s = NULL;
        double q[5], wc, t0, dt;
        double ws = 3000.0 * PI / 30.0;
        MUST(ehl_element_equilibrium(el[1], c3000, q, NULL, NULL));
        MUST(ehl_element_cage_speed(el[1], ws, 0.0, &wc));
        MUST(ehl_state_new(&s));
        memset(&in, 0, sizeof in);
        memcpy(in.displacement, q, sizeof q);
        in.velocity[0] = 1e-4;
        in.velocity[1] = -2e-4;
        in.velocity[2] = 1e-4;
        in.velocity[3] = 1e-3;
        in.velocity[4] = -1e-3;
        in.inner_speed_rad_s = ws;
        MUST(ehl_evaluate(el[1], s, &in, &out));
        t0 = now_s();
        for (i = 1; i <= calls; i++) {
            double t = (double)i * 1e-5;
            in.displacement[1] = q[1] + 1e-8 * sin(1e3 * t);
            in.cage_angle_rad = wc * t;
            MUST(ehl_evaluate(el[1], s, &in, &out));
        }
        dt = now_s() - t0;
        printf("force element through C (fitted laws with damping, warm state): %ld calls, %.2f us per call\n",
               calls, 1e6 * dt / (double)(calls > 0 ? calls : 1));
        ehl_state_free(s);
    }

    {
        int i;
        for (i = 0; i < NAMES; i++) {
            ehl_element_free(el[i]);
            ehl_state_free(st[i]);
        }
    }
    ehl_characterization_free(ch);
    ehl_case_free(c3000);
    ehl_case_free(c);
    printf("%d passed, %d failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}
