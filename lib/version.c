/* version.c - build provenance recorded in every store's /Code group (values from the Makefile). */
#include "cli.h"

#ifndef VRES_VERSION
#define VRES_VERSION "0.0.0"
#endif
#ifndef VRES_GIT
#define VRES_GIT "unknown"
#endif
#ifndef VRES_CFLAGS
#define VRES_CFLAGS ""
#endif
#ifdef VRES_HAVE_CUDA
#define FEATURE_CUDA " cuda"
#else
#define FEATURE_CUDA ""
#endif
#ifdef _OPENMP
#define FEATURE_OMP "openmp"
#else
#define FEATURE_OMP "serial"
#endif

const char vres_version[] = VRES_VERSION;
const char vres_git_revision[] = VRES_GIT;
const char vres_compiler[] = "gcc " __VERSION__;
const char vres_cflags[] = VRES_CFLAGS;
const char vres_features[] = FEATURE_OMP FEATURE_CUDA " hdf5 libxml2 vtk";
