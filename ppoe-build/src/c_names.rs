//! Which names a C table may use: every identifier a table `NAME` defines (`NAME`,
//! `NAME_F32`, `NAME_JOINTS`, `NAME_F32_JOINTS`, the macro `NAME_N_JOINTS`, the include
//! guard `PPOE_TABLE_NAME_H`) must compile wherever the header is included, so none may be a
//! keyword or a name the headers it includes already define.
//!
//! The choice is to refuse such a name with an error saying why, not to derive another
//! one: a derived name would be one the user never wrote and would have to look up in the
//! output to call the table. The rules:
//!
//! * keywords of C89 to C23, the GNU `asm`, and C++'s (`ppoe.h` is usable from C++, so a
//!   table header should be too);
//! * reserved identifiers: a leading `_` (reserved at file scope, where the table's names
//!   are) and `__` anywhere (reserved in C at the start, in C++ anywhere);
//! * the namespace of `ppoe.h`: every identifier it defines starts with `PPOE_` or
//!   `ppoe_`, so both prefixes are refused, in any case;
//! * the headers the table includes: `<math.h>` (the functions of C99 with their `f` and `l`
//!   forms, its macros, `FP_*`, and the extras glibc and newlib declare outside strict ISO
//!   mode: `M_PI`, `j0`, `DOMAIN`, …), and through `ppoe.h` `<stddef.h>` and `<stdint.h>`
//!   (`NULL`, `offsetof`, every `*_t`, `INT*`/`UINT*` names ending in `_MAX`, `_MIN` or
//!   `_C`, `SIZE_MAX`, …).

use crate::error::{Error, ErrorKind, Result};

/// Keywords of C89–C23 (with GNU's `asm`) and of C++.
const KEYWORDS: &[&str] = &[
    // C89
    "auto",
    "break",
    "case",
    "char",
    "const",
    "continue",
    "default",
    "do",
    "double",
    "else",
    "enum",
    "extern",
    "float",
    "for",
    "goto",
    "if",
    "int",
    "long",
    "register",
    "return",
    "short",
    "signed",
    "sizeof",
    "static",
    "struct",
    "switch",
    "typedef",
    "union",
    "unsigned",
    "void",
    "volatile",
    "while", // C99, C11
    "inline",
    "restrict",
    "_Bool",
    "_Complex",
    "_Imaginary",
    "_Alignas",
    "_Alignof",
    "_Atomic",
    "_Generic",
    "_Noreturn",
    "_Static_assert",
    "_Thread_local", // C23 and <stdbool.h> etc.
    "bool",
    "true",
    "false",
    "alignas",
    "alignof",
    "constexpr",
    "nullptr",
    "static_assert",
    "thread_local",
    "typeof",
    "typeof_unqual",
    "noreturn",
    "complex",
    "imaginary",
    "asm",
    // C++
    "and",
    "and_eq",
    "bitand",
    "bitor",
    "catch",
    "char8_t",
    "char16_t",
    "char32_t",
    "class",
    "co_await",
    "co_return",
    "co_yield",
    "compl",
    "concept",
    "const_cast",
    "consteval",
    "constinit",
    "decltype",
    "delete",
    "dynamic_cast",
    "explicit",
    "export",
    "friend",
    "mutable",
    "namespace",
    "new",
    "noexcept",
    "not",
    "not_eq",
    "operator",
    "or",
    "or_eq",
    "private",
    "protected",
    "public",
    "reinterpret_cast",
    "requires",
    "static_cast",
    "template",
    "this",
    "throw",
    "try",
    "typeid",
    "typename",
    "using",
    "virtual",
    "wchar_t",
    "xor",
    "xor_eq",
];

/// The functions of C99's `<math.h>`; each also exists with an `f` and an `l` suffix.
const MATH_FUNCTIONS: &[&str] = &[
    "acos",
    "asin",
    "atan",
    "atan2",
    "cos",
    "sin",
    "tan",
    "acosh",
    "asinh",
    "atanh",
    "cosh",
    "sinh",
    "tanh",
    "exp",
    "exp2",
    "expm1",
    "frexp",
    "ilogb",
    "ldexp",
    "log",
    "log10",
    "log1p",
    "log2",
    "logb",
    "modf",
    "scalbn",
    "scalbln",
    "cbrt",
    "fabs",
    "hypot",
    "pow",
    "sqrt",
    "erf",
    "erfc",
    "lgamma",
    "tgamma",
    "ceil",
    "floor",
    "nearbyint",
    "rint",
    "lrint",
    "llrint",
    "round",
    "lround",
    "llround",
    "trunc",
    "fmod",
    "remainder",
    "remquo",
    "copysign",
    "nan",
    "nextafter",
    "nexttoward",
    "fdim",
    "fmax",
    "fmin",
    "fma",
    // glibc and newlib outside strict ISO mode
    "j0",
    "j1",
    "jn",
    "y0",
    "y1",
    "yn",
    "gamma",
    "drem",
    "finite",
    "significand",
    "scalb",
    "exp10",
    "pow10",
    "sincos",
    "lgamma_r",
    "gamma_r",
    "isinf",
    "isnan",
];

/// Other names `<math.h>`, `<stddef.h>` and `<stdint.h>` define (macros, types, objects).
const HEADER_NAMES: &[&str] = &[
    // <math.h>
    "INFINITY",
    "NAN",
    "HUGE_VAL",
    "HUGE_VALF",
    "HUGE_VALL",
    "MATH_ERRNO",
    "MATH_ERREXCEPT",
    "math_errhandling",
    "fpclassify",
    "isfinite",
    "isnormal",
    "signbit",
    "isgreater",
    "isgreaterequal",
    "isless",
    "islessequal",
    "islessgreater",
    "isunordered",
    "HUGE",
    "MAXFLOAT",
    "DOMAIN",
    "SING",
    "OVERFLOW",
    "UNDERFLOW",
    "TLOSS",
    "PLOSS",
    "X_TLOSS",
    "signgam",
    "exception",
    "matherr",
    "M_E",
    "M_LOG2E",
    "M_LOG10E",
    "M_LN2",
    "M_LN10",
    "M_PI",
    "M_PI_2",
    "M_PI_4",
    "M_1_PI",
    "M_2_PI",
    "M_2_SQRTPI",
    "M_SQRT2",
    "M_SQRT1_2",
    // <stddef.h>, <stdint.h>
    "NULL",
    "offsetof",
    "PTRDIFF_MIN",
    "PTRDIFF_MAX",
    "SIG_ATOMIC_MIN",
    "SIG_ATOMIC_MAX",
    "SIZE_MAX",
    "WCHAR_MIN",
    "WCHAR_MAX",
    "WINT_MIN",
    "WINT_MAX",
];

/// Every identifier the C table `name` defines.
pub fn defined_identifiers(name: &str) -> [String; 6] {
    [
        name.to_string(),
        format!("{name}_F32"),
        format!("{name}_JOINTS"),
        format!("{name}_F32_JOINTS"),
        format!("{name}_N_JOINTS"),
        format!("PPOE_TABLE_{name}_H"),
    ]
}

/// Checks that a C table may be called `name` (which must already be a valid const name,
/// [`crate::literal::check_const_name`]): none of the identifiers it defines breaks the
/// rules of this module.
///
/// # Errors
///
/// [`ErrorKind::Config`] naming the table name, the identifier and the rule.
pub fn check_c_name(name: &str) -> Result<()> {
    let own = format!("PPOE_TABLE_{name}_H");
    for id in defined_identifiers(name) {
        // The include guard is in ppoe's namespace on purpose; its other rules still apply.
        let why = if id == own {
            collision(name).or_else(|| reserved(&id))
        } else {
            collision(&id).or_else(|| reserved(&id))
        };
        if let Some(why) = why {
            let what = if id == name {
                String::new()
            } else {
                format!(" (its identifier `{id}`)")
            };
            return Err(Error::new(
                ErrorKind::Config,
                format!(
                    "{name:?} is not usable as a C table name{what}: {why}; choose another name"
                ),
            ));
        }
    }
    Ok(())
}

/// Why `id` collides with a keyword or a name of the included headers, if it does.
fn collision(id: &str) -> Option<String> {
    let lower = id.to_ascii_lowercase();
    if KEYWORDS.contains(&id) {
        return Some(format!("`{id}` is a C or C++ keyword"));
    }
    if lower.starts_with("ppoe_") {
        return Some("names starting with PPOE_ or ppoe_ belong to ppoe.h".into());
    }
    let is_math_function = |f: &str| {
        MATH_FUNCTIONS
            .iter()
            .any(|m| f == *m || f.strip_prefix(m).is_some_and(|s| s == "f" || s == "l"))
    };
    if is_math_function(id) || HEADER_NAMES.contains(&id) {
        return Some(format!(
            "`{id}` is defined by a standard header the table includes"
        ));
    }
    if id.starts_with("FP_") || id.ends_with("_t") {
        return Some(format!(
            "`{id}` is in the namespace of <math.h> (FP_*) or of the standard types (*_t)"
        ));
    }
    let int_macro = (id.starts_with("INT") || id.starts_with("UINT"))
        && (id.ends_with("_MAX") || id.ends_with("_MIN") || id.ends_with("_C"));
    int_macro.then(|| format!("`{id}` is in the namespace of <stdint.h>'s limit macros"))
}

/// Why `id` is a reserved identifier, if it is.
fn reserved(id: &str) -> Option<String> {
    if id.starts_with('_') {
        Some(format!("`{id}` starts with `_`, reserved at file scope"))
    } else if id.contains("__") {
        Some(format!(
            "`{id}` contains `__`, reserved (in C at the start, in C++ anywhere)"
        ))
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_keywords_reserved_and_header_names() {
        for bad in [
            "int",
            "_Bool",
            "bool",
            "nullptr",
            "class",
            "_X",
            "A__B",
            "A_",
            "PPOE_OK",
            "ppoe_x",
            "Ppoe_y",
            "NULL",
            "offsetof",
            "size_t",
            "uint8_t",
            "INFINITY",
            "NAN",
            "HUGE_VAL",
            "FP_NAN",
            "sin",
            "cosf",
            "expl",
            "M_PI",
            "INT8_MAX",
            "UINTPTR_MAX",
            "INT64_C",
            "SIZE_MAX",
            "OVERFLOW",
        ] {
            let e = check_c_name(bad).unwrap_err();
            assert_eq!(e.kind(), ErrorKind::Config, "{bad}");
            assert!(e.message().contains(&format!("{bad:?}")), "{e}");
        }
        for good in [
            "SEED", "R", "ARM7", "sine", "INT", "x_T", "TABLE", "robot_1",
        ] {
            assert!(check_c_name(good).is_ok(), "{good}");
        }
    }
}
