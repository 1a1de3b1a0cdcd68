/*
 * ehl_mex.c — MEX gateway of the ehl-bearing C interface for MATLAB and GNU Octave (one
 * source: `mex` in MATLAB, `mkoctfile --mex` in Octave; see ehl_build_mex.m).
 *
 * Called as ehl_mex(COMMAND, ...) by the .m functions beside it (ehl_case, ehl_element,
 * ehl_evaluate, ...), which are the interface to use. Library objects (cases, elements, states,
 * characterizations) live in a table inside this MEX file and are named by a numeric id; an id
 * that is not in the table (freed, or from an earlier session) is an error, never a crash.
 * ehl_free releases objects; clearing the MEX file (clear ehl_mex, clear all) releases all.
 *
 * Errors are MATLAB errors with the library's message and an identifier per status:
 * ehl:null, ehl:argument, ehl:input, ehl:compute, ehl:cancelled, ehl:internal; usage errors of
 * this gateway are ehl:usage. No MATLAB error is raised while the library is running (the
 * progress callback is called with mexCallMATLABWithTrap and its error re-raised afterwards).
 */
#include "mex.h"
#include "ehl_bearing.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ---------------------------------------------------------------------------------------- */
/* Object table                                                                              */
/* ---------------------------------------------------------------------------------------- */

enum { T_CASE = 1, T_ELEMENT, T_STATE, T_CHARACTERIZATION };
static const char *type_names[] = {"", "case", "element", "state", "characterization"};

typedef struct {
    double id;
    int type;
    void *ptr;
} Entry;

static Entry *table = NULL;
static size_t table_len = 0, table_cap = 0;
static double next_id = 0.0;

static void release(Entry *e) {
    switch (e->type) {
    case T_CASE: ehl_case_free((EhlCase *)e->ptr); break;
    case T_ELEMENT: ehl_element_free((EhlElement *)e->ptr); break;
    case T_STATE: ehl_state_free((EhlState *)e->ptr); break;
    case T_CHARACTERIZATION: ehl_characterization_free((EhlCharacterization *)e->ptr); break;
    default: break;
    }
    e->ptr = NULL;
    e->type = 0;
}

static void clear_all(void) {
    size_t i;
    for (i = 0; i < table_len; i++) release(&table[i]);
    free(table);
    table = NULL;
    table_len = table_cap = 0;
}

static double add(int type, void *ptr) {
    if (next_id == 0.0) {
        /* Ids of different sessions differ, so a stale id never names a new object. */
        next_id = (double)((unsigned long)time(NULL) % 100000UL) * 1e6 + 1.0;
        mexAtExit(clear_all);
    }
    if (table_len == table_cap) {
        size_t cap = table_cap ? 2 * table_cap : 64;
        Entry *t = (Entry *)realloc(table, cap * sizeof(Entry));
        if (!t) {
            /* Release the new object before raising: nothing leaks. */
            Entry tmp;
            tmp.id = 0;
            tmp.type = type;
            tmp.ptr = ptr;
            release(&tmp);
            mexErrMsgIdAndTxt("ehl:internal", "out of memory for the object table");
        }
        table = t;
        table_cap = cap;
    }
    table[table_len].id = next_id;
    table[table_len].type = type;
    table[table_len].ptr = ptr;
    table_len++;
    return next_id++;
}

static Entry *find(double id) {
    size_t i;
    for (i = 0; i < table_len; i++)
        if (table[i].id == id && table[i].type != 0) return &table[i];
    return NULL;
}

static void remove_entry(Entry *e) {
    release(e);
    *e = table[table_len - 1];
    table_len--;
}

/* ---------------------------------------------------------------------------------------- */
/* Arguments                                                                                 */
/* ---------------------------------------------------------------------------------------- */

static const char *status_id(int st) {
    switch (st) {
    case EHL_ERR_NULL: return "ehl:null";
    case EHL_ERR_ARGUMENT: return "ehl:argument";
    case EHL_ERR_INPUT: return "ehl:input";
    case EHL_ERR_COMPUTE: return "ehl:compute";
    case EHL_ERR_CANCELLED: return "ehl:cancelled";
    default: return "ehl:internal";
    }
}

/* Raise the library's error of status st as a MATLAB error. */
static void raise(int st) {
    mexErrMsgIdAndTxt(status_id(st), "%s", ehl_last_error());
}

#define CALL(call)                                                                            \
    do {                                                                                      \
        int st_ = (call);                                                                     \
        if (st_ != EHL_OK) raise(st_);                                                        \
    } while (0)

static void need(int nrhs, int n, const char *usage) {
    if (nrhs < n) mexErrMsgIdAndTxt("ehl:usage", "not enough arguments: %s", usage);
}

/* Text argument (mxMalloc'd; freed when the MEX call returns). */
static char *text_arg(const mxArray *a, const char *name) {
    char *s;
    if (!mxIsChar(a)) mexErrMsgIdAndTxt("ehl:usage", "%s must be text (a char row vector)", name);
    s = mxArrayToString(a);
    if (!s) mexErrMsgIdAndTxt("ehl:usage", "%s could not be read as text", name);
    return s;
}

/* Text argument, or NULL for an empty array. */
static char *text_or_empty(const mxArray *a, const char *name) {
    if (mxIsEmpty(a)) return NULL;
    return text_arg(a, name);
}

static double scalar_arg(const mxArray *a, const char *name) {
    if (!mxIsDouble(a) || mxIsComplex(a) || mxGetNumberOfElements(a) != 1)
        mexErrMsgIdAndTxt("ehl:usage", "%s must be a real double scalar", name);
    return mxGetScalar(a);
}

static void vector_arg(const mxArray *a, const char *name, double *out, size_t n) {
    if (!mxIsDouble(a) || mxIsComplex(a) || mxGetNumberOfElements(a) != n)
        mexErrMsgIdAndTxt("ehl:usage", "%s must be a real double vector of %u elements", name,
                          (unsigned)n);
    memcpy(out, mxGetPr(a), n * sizeof(double));
}

/* The object behind an id (a number, or a struct with field "id"), of type `type`. */
static void *object_arg(const mxArray *a, int type, const char *name) {
    const mxArray *idf = a;
    Entry *e;
    if (mxIsStruct(a)) {
        idf = mxGetField(a, 0, "id");
        if (!idf) mexErrMsgIdAndTxt("ehl:usage", "%s: a struct without field id", name);
    }
    if (!mxIsDouble(idf) || mxGetNumberOfElements(idf) != 1)
        mexErrMsgIdAndTxt("ehl:usage", "%s must be an ehl-bearing %s (from ehl_%s)", name,
                          type_names[type], type_names[type]);
    e = find(mxGetScalar(idf));
    if (!e)
        mexErrMsgIdAndTxt("ehl:usage",
                          "%s: no ehl-bearing object with id %.0f (freed, or from before the MEX "
                          "file was cleared)",
                          name, mxGetScalar(idf));
    if (e->type != type)
        mexErrMsgIdAndTxt("ehl:usage", "%s is an ehl-bearing %s, not an ehl-bearing %s", name,
                          type_names[e->type], type_names[type]);
    return e->ptr;
}

/* 5×5 row-major → MATLAB column-major. */
static mxArray *matrix5(const double *m) {
    mxArray *a = mxCreateDoubleMatrix(5, 5, mxREAL);
    double *p = mxGetPr(a);
    int i, j;
    for (i = 0; i < 5; i++)
        for (j = 0; j < 5; j++) p[i + 5 * j] = m[5 * i + j];
    return a;
}

static mxArray *vector(const double *v, int n) {
    mxArray *a = mxCreateDoubleMatrix(n, 1, mxREAL);
    memcpy(mxGetPr(a), v, (size_t)n * sizeof(double));
    return a;
}

/* Library-owned text → MATLAB char array; the library string is freed. */
static mxArray *take_text(char *s) {
    mxArray *a = mxCreateString(s);
    ehl_string_free(s);
    return a;
}

/* ---------------------------------------------------------------------------------------- */
/* Progress callback                                                                         */
/* ---------------------------------------------------------------------------------------- */

typedef struct {
    const mxArray *fn;   /* a function handle, called as stop = fn(event_json) */
    mxArray *exception;  /* its error, raised after the library returns */
} Callback;

static int on_progress(const char *event_json, void *user) {
    Callback *cb = (Callback *)user;
    mxArray *in[2], *out[1] = {NULL}, *ex;
    int stop = 0;
    if (cb->exception) return 1;
    in[0] = (mxArray *)cb->fn;
    in[1] = mxCreateString(event_json);
    ex = mexCallMATLABWithTrap(1, out, 2, in, "feval");
    mxDestroyArray(in[1]);
    if (ex) {
        cb->exception = ex;
        return 1;
    }
    if (out[0]) {
        stop = !mxIsEmpty(out[0]) && (mxIsLogical(out[0]) || mxIsNumeric(out[0])) &&
               mxGetScalar(out[0]) != 0.0;
        mxDestroyArray(out[0]);
    }
    return stop;
}

static void callback_init(Callback *cb, int nrhs, const mxArray *prhs[], int at) {
    cb->fn = NULL;
    cb->exception = NULL;
    if (nrhs > at && !mxIsEmpty(prhs[at])) {
        if (mxGetClassID(prhs[at]) != mxFUNCTION_CLASS)
            mexErrMsgIdAndTxt("ehl:usage", "progress must be a function handle");
        cb->fn = prhs[at];
    }
}

/* After the library call: re-raise the callback's own error, then the library's. */
static void callback_done(Callback *cb, int st) {
    if (cb->exception) {
        mxArray *in[1];
        in[0] = cb->exception;
        mexCallMATLAB(0, NULL, 1, in, "rethrow");
    }
    if (st != EHL_OK) raise(st);
}

/* ---------------------------------------------------------------------------------------- */
/* Commands                                                                                  */
/* ---------------------------------------------------------------------------------------- */

static mxArray *case_struct(EhlCase *c) {
    static const char *fields[] = {"id", "type", "ball_count", "ball_diameter_m", "pitch_diameter_m",
                                   "contact_angle_rad", "inner_speed_rad_s", "outer_speed_rad_s"};
    EhlCaseInfo info;
    mxArray *s;
    int st = ehl_case_info(c, &info);
    if (st != EHL_OK) {
        ehl_case_free(c);
        raise(st);
    }
    s = mxCreateStructMatrix(1, 1, 8, fields);
    mxSetField(s, 0, "id", mxCreateDoubleScalar(add(T_CASE, c)));
    mxSetField(s, 0, "type", mxCreateString("ehl_case"));
    mxSetField(s, 0, "ball_count", mxCreateDoubleScalar(info.ball_count));
    mxSetField(s, 0, "ball_diameter_m", mxCreateDoubleScalar(info.ball_diameter_m));
    mxSetField(s, 0, "pitch_diameter_m", mxCreateDoubleScalar(info.pitch_diameter_m));
    mxSetField(s, 0, "contact_angle_rad", mxCreateDoubleScalar(info.contact_angle_rad));
    mxSetField(s, 0, "inner_speed_rad_s", mxCreateDoubleScalar(info.inner_speed_rad_s));
    mxSetField(s, 0, "outer_speed_rad_s", mxCreateDoubleScalar(info.outer_speed_rad_s));
    return s;
}

static mxArray *element_struct(EhlElement *e) {
    static const char *fields[] = {"id", "type", "kind", "has_damping", "ball_count",
                                   "ball_diameter_m", "pitch_diameter_m", "state"};
    static const char *kinds[] = {"dry", "fitted", "trend"};
    EhlElementInfo info;
    EhlState *state = NULL;
    mxArray *s;
    int st = ehl_element_info(e, &info);
    if (st == EHL_OK) st = ehl_state_new(&state);
    if (st != EHL_OK) {
        ehl_element_free(e);
        raise(st);
    }
    s = mxCreateStructMatrix(1, 1, 8, fields);
    mxSetField(s, 0, "id", mxCreateDoubleScalar(add(T_ELEMENT, e)));
    mxSetField(s, 0, "type", mxCreateString("ehl_element"));
    mxSetField(s, 0, "kind", mxCreateString(kinds[info.kind >= 0 && info.kind <= 2 ? info.kind : 0]));
    mxSetField(s, 0, "has_damping", mxCreateLogicalScalar(info.has_damping != 0));
    mxSetField(s, 0, "ball_count", mxCreateDoubleScalar(info.ball_count));
    mxSetField(s, 0, "ball_diameter_m", mxCreateDoubleScalar(info.ball_diameter_m));
    mxSetField(s, 0, "pitch_diameter_m", mxCreateDoubleScalar(info.pitch_diameter_m));
    mxSetField(s, 0, "state", mxCreateDoubleScalar(add(T_STATE, state)));
    return s;
}

static void cmd_evaluate(int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[]) {
    EhlInput in;
    EhlOutput out;
    EhlElement *e;
    EhlState *s;
    need(nrhs, 8, "ehl_mex('evaluate', element, state, q, qdot, inner_speed, outer_speed, cage_angle)");
    e = (EhlElement *)object_arg(prhs[1], T_ELEMENT, "element");
    s = (EhlState *)object_arg(prhs[2], T_STATE, "state");
    vector_arg(prhs[3], "q", in.displacement, 5);
    vector_arg(prhs[4], "qdot", in.velocity, 5);
    in.inner_speed_rad_s = scalar_arg(prhs[5], "inner_speed_rad_s");
    in.outer_speed_rad_s = scalar_arg(prhs[6], "outer_speed_rad_s");
    in.cage_angle_rad = scalar_arg(prhs[7], "cage_angle_rad");
    CALL(ehl_evaluate(e, s, &in, &out));
    plhs[0] = vector(out.reaction, 5);
    if (nlhs > 1) plhs[1] = matrix5(out.stiffness);
    if (nlhs > 2) plhs[2] = matrix5(out.damping);
    if (nlhs > 3) {
        static const char *fields[] = {"outside_range", "overloaded", "speed_outside",
                                       "cage_speed_rad_s"};
        mxArray *info = mxCreateStructMatrix(1, 1, 4, fields);
        mxSetField(info, 0, "outside_range", mxCreateDoubleScalar(out.outside_range));
        mxSetField(info, 0, "overloaded", mxCreateDoubleScalar(out.overloaded));
        mxSetField(info, 0, "speed_outside", mxCreateLogicalScalar(out.speed_outside != 0));
        mxSetField(info, 0, "cage_speed_rad_s", mxCreateDoubleScalar(out.cage_speed_rad_s));
        plhs[3] = info;
    }
}

void mexFunction(int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[]) {
    char cmd[64];
    if (nrhs < 1 || !mxIsChar(prhs[0]) || mxGetString(prhs[0], cmd, sizeof cmd) != 0)
        mexErrMsgIdAndTxt("ehl:usage", "ehl_mex(COMMAND, ...): COMMAND must be text; use the "
                                       "ehl_*.m functions");
    if (strcmp(cmd, "evaluate") == 0) {
        cmd_evaluate(nlhs, plhs, nrhs, prhs);
    } else if (strcmp(cmd, "version") == 0) {
        plhs[0] = mxCreateString(ehl_version());
    } else if (strcmp(cmd, "case_file") == 0 || strcmp(cmd, "case_toml") == 0) {
        EhlCase *c = NULL;
        need(nrhs, 2, "ehl_mex('case_file', path) or ehl_mex('case_toml', text)");
        if (cmd[5] == 'f')
            CALL(ehl_case_from_file(text_arg(prhs[1], "path"), &c));
        else
            CALL(ehl_case_from_toml(text_arg(prhs[1], "toml"), "<toml text>", &c));
        plhs[0] = case_struct(c);
    } else if (strcmp(cmd, "case_speed") == 0) {
        EhlCase *c = NULL;
        need(nrhs, 3, "ehl_mex('case_speed', case, inner_speed_rpm)");
        CALL(ehl_case_with_inner_speed_rpm((EhlCase *)object_arg(prhs[1], T_CASE, "case"),
                                           scalar_arg(prhs[2], "inner_speed_rpm"), &c));
        plhs[0] = case_struct(c);
    } else if (strcmp(cmd, "case_equilibrium") == 0) {
        char *json = NULL;
        need(nrhs, 2, "ehl_mex('case_equilibrium', case)");
        CALL(ehl_case_equilibrium_json((EhlCase *)object_arg(prhs[1], T_CASE, "case"), &json));
        plhs[0] = take_text(json);
    } else if (strcmp(cmd, "characterize") == 0) {
        EhlCharacterization *ch = NULL;
        Callback cb;
        char *json = NULL;
        int st;
        EhlCase *c;
        char *method;
        need(nrhs, 2, "ehl_mex('characterize', case, method, progress)");
        c = (EhlCase *)object_arg(prhs[1], T_CASE, "case");
        method = nrhs > 2 ? text_or_empty(prhs[2], "method") : NULL;
        callback_init(&cb, nrhs, prhs, 3);
        st = ehl_characterize(c, method, cb.fn ? on_progress : NULL, &cb, &ch);
        callback_done(&cb, st);
        st = ehl_characterization_json(ch, 1, &json);
        if (st != EHL_OK) {
            ehl_characterization_free(ch);
            raise(st);
        }
        plhs[0] = mxCreateDoubleScalar(add(T_CHARACTERIZATION, ch));
        if (nlhs > 1) plhs[1] = take_text(json);
        else ehl_string_free(json);
    } else if (strncmp(cmd, "element_", 8) == 0) {
        EhlElement *e = NULL;
        const char *k = cmd + 8;
        if (strcmp(k, "hertz") == 0) {
            need(nrhs, 2, "ehl_mex('element_hertz', case)");
            CALL(ehl_element_hertz((EhlCase *)object_arg(prhs[1], T_CASE, "case"), &e));
        } else if (strcmp(k, "characterization") == 0) {
            need(nrhs, 2, "ehl_mex('element_characterization', characterization)");
            CALL(ehl_element_from_characterization(
                (EhlCharacterization *)object_arg(prhs[1], T_CHARACTERIZATION, "characterization"), &e));
        } else if (strcmp(k, "report_file") == 0 || strcmp(k, "report_json") == 0) {
            EhlCase *c;
            char *t;
            need(nrhs, 3, "ehl_mex('element_report_file', case, path)");
            c = (EhlCase *)object_arg(prhs[1], T_CASE, "case");
            t = text_arg(prhs[2], "report");
            if (k[7] == 'f') CALL(ehl_element_from_report_file(c, t, &e));
            else CALL(ehl_element_from_report_json(c, t, &e));
        } else if (strcmp(k, "trend_file") == 0 || strcmp(k, "trend_json") == 0) {
            char *t;
            need(nrhs, 2, "ehl_mex('element_trend_file', path)");
            t = text_arg(prhs[1], "trends");
            if (k[6] == 'f') CALL(ehl_element_trend_from_file(t, &e));
            else CALL(ehl_element_trend_from_json(t, &e));
        } else {
            mexErrMsgIdAndTxt("ehl:usage", "unknown command %s", cmd);
        }
        plhs[0] = element_struct(e);
    } else if (strcmp(cmd, "state") == 0) {
        EhlState *s = NULL;
        CALL(ehl_state_new(&s));
        plhs[0] = mxCreateDoubleScalar(add(T_STATE, s));
    } else if (strcmp(cmd, "cage_speed") == 0) {
        double w = 0.0;
        need(nrhs, 4, "ehl_mex('cage_speed', element, inner_speed_rad_s, outer_speed_rad_s)");
        CALL(ehl_element_cage_speed((EhlElement *)object_arg(prhs[1], T_ELEMENT, "element"),
                                    scalar_arg(prhs[2], "inner_speed_rad_s"),
                                    scalar_arg(prhs[3], "outer_speed_rad_s"), &w));
        plhs[0] = mxCreateDoubleScalar(w);
    } else if (strcmp(cmd, "equilibrium") == 0) {
        double q[5], k[25], c[25];
        need(nrhs, 3, "ehl_mex('equilibrium', element, case)");
        CALL(ehl_element_equilibrium((EhlElement *)object_arg(prhs[1], T_ELEMENT, "element"),
                                     (EhlCase *)object_arg(prhs[2], T_CASE, "case"), q, k, c));
        plhs[0] = vector(q, 5);
        if (nlhs > 1) plhs[1] = matrix5(k);
        if (nlhs > 2) plhs[2] = matrix5(c);
    } else if (strcmp(cmd, "contacts") == 0) {
        double loads[512], appr[512];
        size_t n = 0, j;
        mxArray *a, *b;
        need(nrhs, 2, "ehl_mex('contacts', state)");
        CALL(ehl_state_contacts((EhlState *)object_arg(prhs[1], T_STATE, "state"), loads, appr, 512, &n));
        a = mxCreateDoubleMatrix(n / 2, 2, mxREAL);
        b = mxCreateDoubleMatrix(n / 2, 2, mxREAL);
        for (j = 0; j < n / 2; j++) {
            mxGetPr(a)[j] = loads[2 * j];
            mxGetPr(a)[j + n / 2] = loads[2 * j + 1];
            mxGetPr(b)[j] = appr[2 * j];
            mxGetPr(b)[j + n / 2] = appr[2 * j + 1];
        }
        plhs[0] = a;
        if (nlhs > 1) plhs[1] = b;
        else mxDestroyArray(b);
    } else if (strcmp(cmd, "characterization_json") == 0) {
        char *json = NULL;
        need(nrhs, 2, "ehl_mex('characterization_json', characterization)");
        CALL(ehl_characterization_json(
            (EhlCharacterization *)object_arg(prhs[1], T_CHARACTERIZATION, "characterization"), 0, &json));
        plhs[0] = take_text(json);
    } else if (strcmp(cmd, "coefficients") == 0) {
        Callback cb;
        char *json = NULL, *method = NULL;
        EhlElement *e = NULL;
        EhlCase *c;
        const mxArray *sp;
        int st;
        need(nrhs, 3, "ehl_mex('coefficients', case, speeds_rpm, method, element, progress)");
        c = (EhlCase *)object_arg(prhs[1], T_CASE, "case");
        sp = prhs[2];
        if (!mxIsDouble(sp) || mxIsComplex(sp) || mxIsEmpty(sp))
            mexErrMsgIdAndTxt("ehl:usage", "speeds_rpm must be a real double vector");
        if (nrhs > 3) method = text_or_empty(prhs[3], "method");
        if (nrhs > 4 && !mxIsEmpty(prhs[4])) e = (EhlElement *)object_arg(prhs[4], T_ELEMENT, "element");
        callback_init(&cb, nrhs, prhs, 5);
        st = ehl_coefficients(c, mxGetPr(sp), mxGetNumberOfElements(sp), method, e,
                              cb.fn ? on_progress : NULL, &cb, &json);
        callback_done(&cb, st);
        plhs[0] = take_text(json);
    } else if (strcmp(cmd, "ross_table") == 0) {
        char *csv = NULL;
        need(nrhs, 2, "ehl_mex('ross_table', coefficients_json)");
        CALL(ehl_ross_table_csv(text_arg(prhs[1], "coefficients_json"), &csv));
        plhs[0] = take_text(csv);
    } else if (strcmp(cmd, "law_maps") == 0) {
        char *json = NULL;
        need(nrhs, 1, "ehl_mex('law_maps')");
        CALL(ehl_law_maps_json(&json));
        plhs[0] = take_text(json);
    } else if (strcmp(cmd, "free") == 0) {
        int i;
        for (i = 1; i < nrhs; i++) {
            const mxArray *a = prhs[i];
            Entry *e;
            if (mxIsStruct(a)) {
                const mxArray *st = mxGetField(a, 0, "state");
                if (st && mxIsDouble(st) && (e = find(mxGetScalar(st))) != NULL) remove_entry(e);
                a = mxGetField(a, 0, "id");
            }
            if (a && mxIsDouble(a) && mxGetNumberOfElements(a) == 1 && (e = find(mxGetScalar(a))) != NULL)
                remove_entry(e);
        }
    } else if (strcmp(cmd, "clear") == 0) {
        clear_all();
    } else if (strcmp(cmd, "count") == 0) {
        plhs[0] = mxCreateDoubleScalar((double)table_len);
    } else {
        mexErrMsgIdAndTxt("ehl:usage", "unknown command %s; use the ehl_*.m functions", cmd);
    }
}
