//! The NC dialects: the controllers' languages formcam writes, and the
//! G-code syntaxes its readers understand. Names and file extensions are
//! parsed here and only here.

use std::fmt;
use std::str::FromStr;

use strum::VariantNames;

use crate::NcError;

/// An NC dialect: what the writers write ([`write`](crate::write)) and
/// whose syntax the readers read ([`read_toolpath`](crate::read_toolpath),
/// [`read_gcode_in`](crate::read_gcode_in)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, strum::IntoStaticStr, strum::VariantNames)]
#[strum(serialize_all = "lowercase")]
pub enum Dialect {
    /// ISO 4343 APT text CLDATA with machine-axis `GOTO` records (`.cls`).
    Cldata,
    /// Siemens Sinumerik 840D part program (`.MPF`): `;` comments, `CR=`
    /// radii, `NAME=value` addresses, keywords on their own lines.
    #[strum(serialize = "sinumerik-840d")]
    Sinumerik840d,
    /// ISO 6983 / Fanuc-style G-code (`.nc`): `(…)` comments, `R` radii.
    Iso,
    /// LinuxCNC rs274ngc (`.ngc`): `(…)` and `;` comments, `R` radii.
    LinuxCnc,
    /// Marlin firmware with axes X, A, B (FiberPath / Cyclone winders)
    /// (`.gcode`); read with the ISO syntax.
    #[strum(serialize = "marlin-xab")]
    MarlinXab,
}

/// Where [`Dialect::names_of`] lists the aliases.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Aliases {
    /// Not at all.
    None,
    /// All of them, after the names.
    Last,
    /// Each after its dialect's name.
    Each,
}

impl Dialect {
    /// Every dialect, in the order of [`Dialect::NAMES`].
    pub const ALL: [Dialect; 5] = [
        Dialect::Cldata,
        Dialect::Sinumerik840d,
        Dialect::Iso,
        Dialect::LinuxCnc,
        Dialect::MarlinXab,
    ];

    /// The dialects' names, in the order of [`Dialect::ALL`].
    pub const NAMES: [&'static str; 5] = Self::names_of::<5>(&Self::ALL, Aliases::None);

    /// Other names taken for a dialect: `fanuc` (ISO), `sinumerik` and
    /// `840d` (Sinumerik 840D).
    const ALIASES: [(&'static str, Dialect); 3] = [
        ("fanuc", Dialect::Iso),
        ("sinumerik", Dialect::Sinumerik840d),
        ("840d", Dialect::Sinumerik840d),
    ];

    /// The dialect called `name` (`"cldata"`, `"sinumerik-840d"`, `"iso"`,
    /// `"linuxcnc"`, `"marlin-xab"`, or an alias: `"fanuc"`, `"sinumerik"`,
    /// `"840d"`), in any case.
    pub fn from_name(name: &str) -> Result<Self, NcError> {
        let lower = name.to_ascii_lowercase();
        Self::NAMES
            .iter()
            .zip(Self::ALL)
            .chain(Self::ALIASES.iter().map(|(n, d)| (n, *d)))
            .find(|(n, _)| **n == lower)
            .map(|(_, d)| d)
            .ok_or_else(|| NcError::UnknownDialect {
                name: name.to_string(),
                allowed: Self::NAMES.join(", "),
            })
    }

    /// The dialect a file extension (without the dot, any case) says:
    /// `cls` CLDATA, `mpf`/`spf` Sinumerik 840D, `nc` ISO, `ngc` LinuxCNC,
    /// `gcode` Marlin X/A/B; `None` for any other.
    pub fn from_extension(ext: &str) -> Option<Self> {
        match ext.to_ascii_lowercase().as_str() {
            "cls" => Some(Self::Cldata),
            "mpf" | "spf" => Some(Self::Sinumerik840d),
            "nc" => Some(Self::Iso),
            "ngc" => Some(Self::LinuxCnc),
            "gcode" => Some(Self::MarlinXab),
            _ => None,
        }
    }

    /// The dialect's name, as [`Dialect::from_name`] takes it.
    pub fn name(self) -> &'static str {
        self.into()
    }

    /// The names of `dialects`, in their order, with the aliases where
    /// `aliases` puts them: the words a field taking these dialects lists.
    /// `N` must be their count.
    pub const fn names_of<const N: usize>(
        dialects: &[Dialect],
        aliases: Aliases,
    ) -> [&'static str; N] {
        let mut out = [""; N];
        let mut k = 0;
        let mut i = 0;
        while i <= dialects.len() {
            let last = i == dialects.len();
            if !last {
                out[k] = Self::VARIANTS[dialects[i] as usize];
                k += 1;
            }
            let mut j = 0;
            while j < Self::ALIASES.len() {
                let take = match aliases {
                    Aliases::None => false,
                    Aliases::Last => last,
                    Aliases::Each => !last && Self::ALIASES[j].1 as usize == dialects[i] as usize,
                };
                if take {
                    out[k] = Self::ALIASES[j].0;
                    k += 1;
                }
                j += 1;
            }
            i += 1;
        }
        assert!(k == N, "N is not the number of names");
        out
    }

    /// The file extension, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            Dialect::Cldata => "cls",
            Dialect::Sinumerik840d => "mpf",
            Dialect::Iso => "nc",
            Dialect::LinuxCnc => "ngc",
            Dialect::MarlinXab => "gcode",
        }
    }
}

impl FromStr for Dialect {
    type Err = NcError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::from_name(s)
    }
}

impl fmt::Display for Dialect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_aliases_and_extensions_lead_to_one_dialect() {
        assert_eq!(
            Dialect::NAMES,
            ["cldata", "sinumerik-840d", "iso", "linuxcnc", "marlin-xab"]
        );
        for (i, d) in Dialect::ALL.into_iter().enumerate() {
            assert_eq!(d as usize, i);
            assert_eq!(Dialect::NAMES[i], d.name());
            assert_eq!(Dialect::from_name(d.name()), Ok(d));
            assert_eq!(Dialect::from_name(&d.name().to_uppercase()), Ok(d));
            assert_eq!(Dialect::from_extension(d.extension()), Some(d));
            assert_eq!(d.to_string().parse::<Dialect>(), Ok(d));
        }
        assert_eq!(Dialect::from_name("fanuc"), Ok(Dialect::Iso));
        assert_eq!(Dialect::from_name("840d"), Ok(Dialect::Sinumerik840d));
        assert_eq!(Dialect::from_name("Sinumerik"), Ok(Dialect::Sinumerik840d));
        assert_eq!(Dialect::from_extension("SPF"), Some(Dialect::Sinumerik840d));
        assert_eq!(Dialect::from_extension("tap"), None);
        let order = [Dialect::Iso, Dialect::Sinumerik840d];
        assert_eq!(
            Dialect::names_of::<5>(&order, Aliases::Last),
            ["iso", "sinumerik-840d", "fanuc", "sinumerik", "840d"]
        );
        assert_eq!(
            Dialect::names_of::<5>(&order, Aliases::Each),
            ["iso", "fanuc", "sinumerik-840d", "sinumerik", "840d"]
        );
        let e = Dialect::from_name("heidenhain").map(|_| ()).unwrap_err();
        assert!(e.to_string().contains("marlin-xab"), "{e}");
    }
}
