/* Shared by the C half of libillume: the Rust entry points (src/ffi) and the varargs helpers. */
#ifndef ILLUME_INTERNAL_H
#define ILLUME_INTERNAL_H
#include "ri.h"
#include <stdarg.h>
#include <stdint.h>

void illume_begin(const char *name);
void illume_end(void);
void illume_call(const char *request);
void illume_float(float f);
void illume_int(int i);
void illume_string(const char *s);
void illume_floats(int n, const float *p);
void illume_ints(int n, const int *p);
void illume_strings(int n, const char *const *p);
void illume_params(int n, const char *const *tokens, const void *const *parms, int uniform,
                   int varying, int vertex, int facevarying);
void illume_send(void);
int illume_handle(void);
void illume_comment(const char *text);
void illume_verbatim(const char *text);
void illume_report(int code, int severity, const char *message);
void illume_user_pixel_filter(RtFilterFunc f, float xwidth, float ywidth);
void illume_archive_records(const char *name, void (*record)(void *, int, const char *),
                            void *context);
int illume_transform_points(const char *from, const char *to, int n, float *points);

/* Most parameters a varargs call may pass; more is an RIE_LIMIT error. */
#define ILLUME_MAXPARAMS 1024

RtInt illume_collect(va_list ap, RtToken tokens[], RtPointer parms[]);

/* Calls `vcall` (using n_, t_, v_) with the token/value pairs after `last`. */
#define ILLUME_VARARGS(last, vcall)                                                            \
  do {                                                                                         \
    RtToken t_[ILLUME_MAXPARAMS];                                                              \
    RtPointer v_[ILLUME_MAXPARAMS];                                                            \
    va_list ap_;                                                                               \
    va_start(ap_, last);                                                                       \
    RtInt n_ = illume_collect(ap_, t_, v_);                                                    \
    va_end(ap_);                                                                               \
    vcall;                                                                                     \
  } while (0)

/* A token/value list whose every class holds one value (shaders, options, attributes). */
void illume_params1(RtInt n, RtToken tokens[], RtPointer parms[]);
/* A primitive's token/value list, sized by its class counts. */
void illume_paramsc(RtInt n, RtToken tokens[], RtPointer parms[], int uniform, int varying,
                    int vertex, int facevarying);
/* The RIB name of a standard filter function; NULL for a program's own function. */
const char *illume_standard_filter(RtFilterFunc f);
/* The RIB name of a filter function; gaussian (with a warning) for a program's own function. */
const char *illume_filter_name(RtFilterFunc f);
/* The current basis steps (for PatchMesh and Curves counts). */
RtInt illume_ustep(void);
RtInt illume_vstep(void);
#endif
