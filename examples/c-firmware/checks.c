/* The checks of the C API: results against the host's f64 expectations (expected.h), and
 * one provoked case per status code. */
#include <math.h>
#include <string.h>

#include "checks.h"
#include "expected.h"
#include "seed_table.h"

#define TOL_F64 1e-12
#define TOL_F32 1e-5

/* max|a-b| / max(1, max|b|); INFINITY if anything is NaN. */
static double rel_err(const double *a, const double *b, int n) {
    double num = 0.0, den = 1.0;
    int i;
    for (i = 0; i < n; i++) {
        double d = fabs(a[i] - b[i]);
        if (d != d) {
            return INFINITY;
        }
        if (d > num) {
            num = d;
        }
        if (fabs(b[i]) > den) {
            den = fabs(b[i]);
        }
    }
    return num / den;
}

__attribute__((noinline)) ppoe_status ppoe_seed_f64(const double *thetas, const double *covs,
                                                    double *pose, double *cov) {
    return ppoe_ppoe_f64(&SEED, thetas, 6, covs, 6, PPOE_CONVENTION_RIGHT, pose, cov);
}

__attribute__((noinline)) ppoe_status ppoe_seed_f32(const float *thetas, const float *covs,
                                                    float *pose, float *cov) {
    return ppoe_ppoe_f32(&SEED_F32, thetas, 6, covs, 6, PPOE_CONVENTION_RIGHT, pose, cov);
}

/* The worse of pose and covariance errors. */
static double result_err(const double *pose, const double *cov, const test_case *c) {
    double ep = rel_err(pose, c->pose, 16), ec = rel_err(cov, c->cov, 36);
    return (ep > ec || ep != ep) ? ep : ec;
}

/* One case in f64: unchecked, checked (must be bit-identical), FK (pose within 1e-12). */
static double case_f64(const test_case *c, int *status_ok) {
    double pose[16], cov[36], pose2[16], cov2[36], fk[16];
    ppoe_status s1 = ppoe_seed_f64(c->thetas, c->covs, pose, cov);
    ppoe_status s2 = ppoe_ppoe_checked_f64(&SEED, c->thetas, 6, c->covs, 6,
                                           PPOE_CONVENTION_RIGHT, pose2, cov2);
    ppoe_status s3 = ppoe_forward_kinematics_f64(&SEED, c->thetas, 6, fk);
    *status_ok = s1 == PPOE_OK && s2 == PPOE_OK && s3 == PPOE_OK &&
                 memcmp(pose, pose2, sizeof pose) == 0 && memcmp(cov, cov2, sizeof cov) == 0 &&
                 rel_err(fk, pose, 16) <= TOL_F64;
    return result_err(pose, cov, c);
}

/* One case in f32: inputs rounded to float, results compared in double. */
static double case_f32(const test_case *c, int *status_ok) {
    float th[6], covs[6 * 36], pose[16], cov[36], pose2[16], cov2[36];
    double pd[16], cd[36];
    int i;
    ppoe_status s1, s2;
    for (i = 0; i < 6; i++) {
        th[i] = (float)c->thetas[i];
    }
    for (i = 0; i < 6 * 36; i++) {
        covs[i] = (float)c->covs[i];
    }
    s1 = ppoe_seed_f32(th, covs, pose, cov);
    s2 = ppoe_ppoe_checked_f32(&SEED_F32, th, 6, covs, 6, PPOE_CONVENTION_RIGHT, pose2, cov2);
    *status_ok = s1 == PPOE_OK && s2 == PPOE_OK && memcmp(pose, pose2, sizeof pose) == 0 &&
                 memcmp(cov, cov2, sizeof cov) == 0;
    for (i = 0; i < 16; i++) {
        pd[i] = pose[i];
    }
    for (i = 0; i < 36; i++) {
        cd[i] = cov[i];
    }
    return result_err(pd, cd, c);
}

int check_cases(void) {
    int k, failures = 0;
    double worst64 = 0.0, worst32 = 0.0;
    for (k = 0; k < N_CASES; k++) {
        const test_case *c = &CASES[k];
        int ok64, ok32, ok;
        double e64 = case_f64(c, &ok64), e32 = case_f32(c, &ok32);
        ok = ok64 && ok32 && e64 <= TOL_F64 && e32 <= TOL_F32;
        failures += !ok;
        worst64 = (e64 > worst64 || e64 != e64) ? e64 : worst64;
        worst32 = (e32 > worst32 || e32 != e32) ? e32 : worst32;
        report("  %-8s f64 %.2e  f32 %.2e  %s", c->name, e64, e32, ok ? "ok" : "MISMATCH");
    }
    report("summary: %d/%d cases passed; worst rel. error f64 %.2e (tol %.0e), f32 %.2e (tol %.0e)",
           N_CASES - failures, N_CASES, worst64, TOL_F64, worst32, TOL_F32);
    return failures;
}

static int expect(const char *what, ppoe_status got, ppoe_status want) {
    if (got != want) {
        report("  status of %s: %d (%s), expected %d (%s)", what, (int)got,
               ppoe_status_message(got), (int)want, ppoe_status_message(want));
        return 1;
    }
    return 0;
}

/* The errors that concern the chain itself, on a modifiable copy of the seed's. */
static int chain_errors(const double *th, const double *covs, double *pose, double *cov) {
    ppoe_joint_f64 joints[SEED_N_JOINTS];
    ppoe_chain_f64 ch = SEED;
    int f = 0, i;
    memcpy(joints, SEED_JOINTS, sizeof joints);
    ch.joints = joints;
    for (i = 0; i < 6; i++) {
        joints[1].screw[i] *= 2.0;
    }
    f += expect("check, doubled screw", ppoe_chain_check_f64(&ch), PPOE_ERR_NOT_UNIT_AXIS);
    f += expect("checked PPOE, doubled screw",
                ppoe_ppoe_checked_f64(&ch, th, 6, covs, 6, 0, pose, cov), PPOE_ERR_NOT_UNIT_AXIS);
    memcpy(joints, SEED_JOINTS, sizeof joints);
    joints[2].axis[0] += 0.5;
    f += expect("check, altered constants", ppoe_chain_check_f64(&ch),
                PPOE_ERR_INCONSISTENT_CONSTANTS);
    memcpy(joints, SEED_JOINTS, sizeof joints);
    joints[0].kind = 9;
    f += expect("joint kind 9", ppoe_chain_check_f64(&ch), PPOE_ERR_BAD_ENUM);
    joints[0].kind = SEED_JOINTS[0].kind;
    joints[3].lower = NAN;
    f += expect("check, NaN limit", ppoe_chain_check_f64(&ch), PPOE_ERR_NON_FINITE);
    memcpy(joints, SEED_JOINTS, sizeof joints);
    ch.home[0][0] = 2.0;
    f += expect("check, home not a rotation", ppoe_chain_check_f64(&ch), PPOE_ERR_NOT_A_ROTATION);
    ch = SEED;
    ch.n_joints = PPOE_MAX_JOINTS + 1;
    f += expect("17 joints", ppoe_chain_check_f64(&ch), PPOE_ERR_TOO_MANY_JOINTS);
    ch = SEED;
    ch.joints = NULL;
    f += expect("NULL joints", ppoe_chain_check_f64(&ch), PPOE_ERR_NULL_POINTER);
    return f;
}

int check_errors(void) {
    const test_case *c = &CASES[5];
    double th[6], covs[6 * 36], pose[16], cov[36];
    float th32[6] = {0, 0, 0, 0, 0, 0}, covs32[6 * 36], pose32[16], cov32[36];
    int f = 0, i;
    memcpy(th, c->thetas, sizeof th);
    memcpy(covs, c->covs, sizeof covs);
    memset(covs32, 0, sizeof covs32);
    f += expect("check SEED", ppoe_chain_check_f64(&SEED), PPOE_OK);
    f += expect("check SEED_F32", ppoe_chain_check_f32(&SEED_F32), PPOE_OK);
    f += expect("check NULL", ppoe_chain_check_f64(NULL), PPOE_ERR_NULL_POINTER);
    f += expect("5 joint values", ppoe_ppoe_f64(&SEED, th, 5, covs, 6, 0, pose, cov),
                PPOE_ERR_LENGTH_MISMATCH);
    f += expect("FK, 7 joint values", ppoe_forward_kinematics_f64(&SEED, th, 7, pose),
                PPOE_ERR_LENGTH_MISMATCH);
    f += expect("convention 7", ppoe_ppoe_f64(&SEED, th, 6, covs, 6, 7, pose, cov),
                PPOE_ERR_BAD_ENUM);
    f += expect("NULL pose", ppoe_ppoe_f64(&SEED, th, 6, covs, 6, 0, NULL, cov),
                PPOE_ERR_NULL_POINTER);
    f += expect("NULL thetas", ppoe_forward_kinematics_f64(&SEED, NULL, 6, pose),
                PPOE_ERR_NULL_POINTER);
    f += expect("NULL covs (f32)", ppoe_ppoe_f32(&SEED_F32, th32, 6, NULL, 6, 0, pose32, cov32),
                PPOE_ERR_NULL_POINTER);
    f += expect("f32 zero covariances", ppoe_ppoe_checked_f32(&SEED_F32, th32, 6, covs32, 6, 1,
                                                               pose32, cov32), PPOE_OK);
    covs[1] += 0.1;
    f += expect("asymmetric covariance",
                ppoe_ppoe_checked_f64(&SEED, th, 6, covs, 6, 0, pose, cov), PPOE_ERR_NOT_SYMMETRIC);
    memset(covs, 0, sizeof covs);
    for (i = 0; i < 6; i++) {
        covs[36 * 2 + 7 * i] = -1.0;
    }
    f += expect("negative covariance", ppoe_ppoe_checked_f64(&SEED, th, 6, covs, 6, 0, pose, cov),
                PPOE_ERR_NOT_POSITIVE_SEMIDEFINITE);
    covs[0] = NAN;
    f += expect("NaN covariance, checked",
                ppoe_ppoe_checked_f64(&SEED, th, 6, covs, 6, 0, pose, cov), PPOE_ERR_NON_FINITE);
    cov[0] = 42.0;
    f += expect("NaN covariance, unchecked (result not finite)",
                ppoe_ppoe_f64(&SEED, th, 6, covs, 6, 0, pose, cov), PPOE_ERR_NON_FINITE);
    f += cov[0] != 42.0; /* nothing written on an error */
    memcpy(covs, c->covs, sizeof covs);
    th[4] = NAN;
    f += expect("NaN joint value, checked",
                ppoe_ppoe_checked_f64(&SEED, th, 6, covs, 6, 0, pose, cov), PPOE_ERR_NON_FINITE);
    f += expect("NaN joint value, FK", ppoe_forward_kinematics_f64(&SEED, th, 6, pose),
                PPOE_ERR_NON_FINITE);
    th[4] = c->thetas[4];
    f += chain_errors(th, covs, pose, cov);
    f += strcmp(ppoe_status_message(12345), "unknown status") != 0;
    f += strcmp(ppoe_status_message(PPOE_OK), "ok") != 0;
    report("errors: %s (every status code provoked once)", f ? "MISMATCH" : "ok");
    return f;
}
