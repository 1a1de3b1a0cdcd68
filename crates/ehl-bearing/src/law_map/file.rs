//! The map file in its two forms: JSON text (one node per line, for reading and diffing) and a
//! compact binary form (the embedded maps: the same numbers, bit for bit, in about a quarter of
//! the bytes). [`LawMap::parse`] reads either; both are checked against the map's spec the same
//! way.
//!
//! The binary form's layout is in [`LawMap::to_binary`].

use super::map::{law_of, values_of, LawKind, LawMap, LawMapSpec, NodeQuality, FORMAT};
use super::LawMapError;
use serde::{Deserialize, Serialize};

/// The first bytes of a map file in the binary form.
pub const BINARY_MAGIC: &[u8; 29] = b"ehl-bearing law map binary 1\n";

/// The binary form's header.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct BinaryHeader {
    spec: LawMapSpec,
    cpu_seconds: f64,
    nodes: usize,
}

/// The names of a record's f64 fields, for messages (ĉ only in maps of the harmonic law).
const LAW_FIELDS: [&str; 7] = [
    "k_hat",
    "d",
    "delta_f_hat",
    "approach_hat",
    "range_hat[0]",
    "range_hat[1]",
    "c_hat",
];

impl LawMap {
    /// Parses a map file in either form (binary if it starts with [`BINARY_MAGIC`], JSON text
    /// otherwise) and checks it against its spec.
    pub fn parse(bytes: &[u8]) -> Result<LawMap, LawMapError> {
        if bytes.starts_with(BINARY_MAGIC) {
            return Self::from_binary(bytes);
        }
        let text = std::str::from_utf8(bytes).map_err(|e| LawMapError::Parse {
            message: format!(
                "neither the binary form (it does not start with {:?}) nor JSON text ({e})",
                std::str::from_utf8(BINARY_MAGIC).expect("ASCII")
            ),
        })?;
        Self::from_json(text)
    }

    /// Parses a map file (JSON) and checks it against its spec.
    pub fn from_json(text: &str) -> Result<LawMap, LawMapError> {
        let m: LawMap = serde_json::from_str(text).map_err(|e| LawMapError::Parse {
            message: e.to_string(),
        })?;
        if m.format != FORMAT {
            return Err(LawMapError::Format {
                format: m.format.clone(),
                expected: FORMAT,
            });
        }
        m.checked()
    }

    /// The map file's text (JSON, one node per line).
    pub fn to_json(&self) -> String {
        let mut s = String::new();
        s.push_str("{\n");
        s.push_str(&format!(
            "\"format\": {},\n",
            serde_json::to_string(&self.format).expect("string")
        ));
        s.push_str(&format!(
            "\"spec\": {},\n",
            serde_json::to_string(&self.spec).expect("spec serializes")
        ));
        let rows = |v: Vec<String>| v.join(",\n");
        s.push_str(&format!(
            "\"laws\": [\n{}\n],\n",
            rows(
                self.laws
                    .iter()
                    .map(|l| serde_json::to_string(l).expect("law"))
                    .collect()
            )
        ));
        s.push_str(&format!(
            "\"quality\": [\n{}\n],\n",
            rows(
                self.quality
                    .iter()
                    .map(|q| serde_json::to_string(q).expect("quality"))
                    .collect()
            )
        ));
        s.push_str(&format!("\"cpu_seconds\": {}\n}}\n", self.cpu_seconds));
        s
    }

    /// The map file in the binary form: the same numbers as [`LawMap::to_json`], bit for bit.
    ///
    /// The binary form, all integers and floats little-endian:
    ///
    /// | bytes | content |
    /// |---|---|
    /// | 29 | [`BINARY_MAGIC`], `"ehl-bearing law map binary 1\n"` |
    /// | 4 | u32 h, the header's length in bytes |
    /// | h | header, JSON: `{"spec": …, "cpu_seconds": …, "nodes": n}` (the spec as in the JSON form) |
    /// | n × r | one record per node in node order (the last axis fastest): K̂, d, ΔF̂, approach, range low, range high, ĉ (a map of the harmonic law only), R², RMS/w0 as f64; converged as one byte, 0 or 1 |
    ///
    /// r = 8·(6 + 2) + 1 = 65 bytes (73 with ĉ). The file's length must be exactly that of its
    /// header and n records.
    pub fn to_binary(&self) -> Vec<u8> {
        let header = serde_json::to_vec(&BinaryHeader {
            spec: self.spec.clone(),
            cpu_seconds: self.cpu_seconds,
            nodes: self.laws.len(),
        })
        .expect("the header serializes");
        let fields = law_fields(&self.spec);
        let mut b = Vec::with_capacity(
            BINARY_MAGIC.len() + 4 + header.len() + self.laws.len() * record_len(fields),
        );
        b.extend_from_slice(BINARY_MAGIC);
        b.extend_from_slice(
            &u32::try_from(header.len())
                .expect("a small header")
                .to_le_bytes(),
        );
        b.extend_from_slice(&header);
        for (l, q) in self.laws.iter().zip(&self.quality) {
            for v in &values_of(l)[..fields] {
                b.extend_from_slice(&v.to_le_bytes());
            }
            b.extend_from_slice(&q.r_squared.to_le_bytes());
            b.extend_from_slice(&q.rms_hat.to_le_bytes());
            b.push(u8::from(q.converged));
        }
        b
    }

    /// Parses a map file in the binary form ([`LawMap::to_binary`]) and checks it against its spec: every
    /// value finite, every converged byte 0 or 1, the length exactly the header's and n records.
    pub fn from_binary(bytes: &[u8]) -> Result<LawMap, LawMapError> {
        let rest =
            bytes
                .strip_prefix(BINARY_MAGIC.as_slice())
                .ok_or_else(|| LawMapError::Parse {
                    message: format!(
                        "not a binary map file: it does not start with {:?}",
                        std::str::from_utf8(BINARY_MAGIC).expect("ASCII")
                    ),
                })?;
        let length = |what: &str, got: usize, expected: usize| {
            LawMapError::Parse {
            message: format!(
                "binary map file: {what}: {got} bytes, expected {expected} (a truncated or damaged file)"
            ),
        }
        };
        let (len, rest) = rest
            .split_first_chunk::<4>()
            .ok_or_else(|| length("header length", rest.len(), 4))?;
        let h = u32::from_le_bytes(*len) as usize;
        if rest.len() < h {
            return Err(length("header", rest.len(), h));
        }
        let (header, records) = rest.split_at(h);
        let header: BinaryHeader =
            serde_json::from_slice(header).map_err(|e| LawMapError::Parse {
                message: format!("binary map file: header: {e}"),
            })?;
        header.spec.validate()?;
        let fields = law_fields(&header.spec);
        let nodes = header.spec.node_count();
        if header.nodes != nodes {
            return Err(LawMapError::NodeCount {
                laws: header.nodes,
                quality: header.nodes,
                nodes,
            });
        }
        let expected = nodes * record_len(fields);
        if records.len() != expected {
            return Err(length(
                &format!("{nodes} node records of {} bytes", record_len(fields)),
                records.len(),
                expected,
            ));
        }
        let harmonic = header.spec.law == LawKind::Harmonic;
        let mut laws = Vec::with_capacity(nodes);
        let mut quality = Vec::with_capacity(nodes);
        for (k, r) in records.chunks_exact(record_len(fields)).enumerate() {
            let mut v = [0.0; 9];
            for (i, x) in v.iter_mut().enumerate().take(fields + 2) {
                *x = f64::from_le_bytes(r[8 * i..8 * i + 8].try_into().expect("8 bytes"));
            }
            if let Some(i) = v[..fields + 2].iter().position(|x| !x.is_finite()) {
                let field = match i.checked_sub(fields) {
                    None => format!("laws[{k}].{}", LAW_FIELDS[i]),
                    Some(0) => format!("quality[{k}].r_squared"),
                    Some(_) => format!("quality[{k}].rms_hat"),
                };
                return Err(LawMapError::Invalid {
                    field,
                    value: v[i],
                    expected: "a finite number".into(),
                });
            }
            let converged = match r[8 * (fields + 2)] {
                0 => false,
                1 => true,
                other => {
                    return Err(LawMapError::Invalid {
                        field: format!("quality[{k}].converged"),
                        value: f64::from(other),
                        expected: "0 or 1".into(),
                    })
                }
            };
            let mut law = [0.0; 7];
            law[..fields].copy_from_slice(&v[..fields]);
            laws.push(law_of(&law, harmonic));
            quality.push(NodeQuality {
                r_squared: v[fields],
                rms_hat: v[fields + 1],
                converged,
            });
        }
        LawMap {
            format: FORMAT.into(),
            spec: header.spec,
            laws,
            quality,
            cpu_seconds: header.cpu_seconds,
        }
        .checked()
    }

    /// The map checked against its spec: valid spec, one law and one quality entry per node, ĉ
    /// given exactly in a map of the harmonic law.
    fn checked(self) -> Result<LawMap, LawMapError> {
        self.spec.validate()?;
        let n = self.spec.node_count();
        if self.laws.len() != n || self.quality.len() != n {
            return Err(LawMapError::NodeCount {
                laws: self.laws.len(),
                quality: self.quality.len(),
                nodes: n,
            });
        }
        let harmonic = self.spec.law == LawKind::Harmonic;
        if let Some(k) = self.laws.iter().position(|l| l.c_hat.is_some() != harmonic) {
            return Err(LawMapError::Invalid {
                field: format!("laws[{k}].c_hat"),
                value: self.laws[k].c_hat.unwrap_or(f64::NAN),
                expected: format!(
                    "{} in a map of the {} law",
                    if harmonic { "a value" } else { "none" },
                    self.spec.law.name()
                ),
            });
        }
        Ok(self)
    }
}

/// The f64 law fields of a record: 7 with ĉ (harmonic law), 6 without.
fn law_fields(spec: &LawMapSpec) -> usize {
    match spec.law {
        LawKind::Harmonic => 7,
        LawKind::QuasiStatic => 6,
    }
}

/// Bytes of one node record with `fields` law fields: those and R², RMS as f64, one byte
/// converged.
fn record_len(fields: usize) -> usize {
    8 * (fields + 2) + 1
}
