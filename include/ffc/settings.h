/* ffc/settings.h: the scene driver's settings: names, types, defaults, admissible values. */
#ifndef FFC_API_SETTINGS_H
#define FFC_API_SETTINGS_H

#include "status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------ driver settings */
/* The settings of the scene driver (scripts/scene.idp), held by the scene
 * with their defaults and admissible values. */
typedef enum { FFC_SET_INT = 0, FFC_SET_REAL = 1, FFC_SET_WORD = 2 } ffc_set_type;
typedef struct {
    const char *name;     /* as a script names it */
    ffc_set_type type;
    double def, lo, hi;   /* default and admissible range (FFC_SET_WORD: the default word's position) */
    int open;             /* bit 1: lo excluded; bit 2: hi excluded */
    const char *words;    /* FFC_SET_WORD: the admissible words, space-separated (NULL otherwise) */
    const char *what;     /* what it sets (one line) */
} ffc_setting;
enum { FFC_NSETTINGS = 64 };  /* room for the settings (ffc_settings_count() <= this) */
typedef struct {
    double v[FFC_NSETTINGS];  /* by position in the table (a word: its position in the list) */
} ffc_settings;
int ffc_settings_count(void);
/* the i-th setting's description (NULL past the end) */
const ffc_setting *ffc_setting_at(int i);
/* the position of a setting, or FFC_ERR_VALUE */
int ffc_setting_find(const char *name);
void ffc_settings_defaults(ffc_settings *s);
/* A setting's value (a number; a word).  FFC_ERR_VALUE with err->msg
 * naming the setting and the value for an unknown name, a value outside
 * its range, a fraction for a whole number, an unknown word. */
int ffc_settings_set(ffc_settings *s, const char *name, double v, ffc_error *err);
int ffc_settings_set_word(ffc_settings *s, const char *name, const char *w, ffc_error *err);
int ffc_settings_get(const ffc_settings *s, const char *name, double *v);
/* a word setting's word into out[cap] (FFC_ERR_CAPACITY when it does not fit) */
int ffc_settings_word(const ffc_settings *s, const char *name, char *out, long cap);

#ifdef __cplusplus
}
#endif
#endif /* FFC_API_SETTINGS_H */
