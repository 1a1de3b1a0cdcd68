//! Flat records as CSV: the one writer of the library's record tables (a study's `results.csv`,
//! the `contacts.csv` of a characterization; re-exported as `report::csv`).
//!
//! A record is a struct or map of cells (`#[serde(flatten)]` parts included); its keys, in field
//! order, are the header. Each cell is written as JSON writes the value (numbers in their shortest
//! round-trip form, booleans as `true`/`false`), text without quotes, and an absent value (`None`,
//! a number that is not finite) as an empty cell.

use serde::ser::{self, Impossible, Serialize};
use std::fmt;

/// `rows` as CSV: the header (the first record's keys) and one line per record; records that are
/// not flat (not a struct or map) are skipped; no records, no text.
pub fn csv<T: Serialize>(rows: &[T]) -> String {
    let mut out = String::new();
    let mut header = false;
    for r in rows {
        let mut row = Row::default();
        if r.serialize(&mut row).is_err() {
            continue;
        }
        if !header {
            out.push_str(&row.keys.join(","));
            out.push('\n');
            header = true;
        }
        out.push_str(&row.cells.join(","));
        out.push('\n');
    }
    out
}

/// One cell: JSON's text of `value`, text unquoted, null empty.
fn cell<T: Serialize + ?Sized>(value: &T) -> Result<String, NotFlat> {
    let json = serde_json::to_string(value).map_err(|_| NotFlat)?;
    Ok(if json == "null" {
        String::new()
    } else if json.starts_with('"') {
        serde_json::from_str::<String>(&json).map_err(|_| NotFlat)?
    } else {
        json
    })
}

/// A value that is not a flat record.
#[derive(Debug)]
struct NotFlat;

impl fmt::Display for NotFlat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("not a flat record")
    }
}

impl std::error::Error for NotFlat {}

impl ser::Error for NotFlat {
    fn custom<M: fmt::Display>(_: M) -> Self {
        NotFlat
    }
}

/// The keys and cells of one record.
#[derive(Default)]
struct Row {
    keys: Vec<String>,
    cells: Vec<String>,
}

impl ser::SerializeStruct for &mut Row {
    type Ok = ();
    type Error = NotFlat;
    fn serialize_field<T: Serialize + ?Sized>(
        &mut self,
        key: &'static str,
        value: &T,
    ) -> Result<(), NotFlat> {
        self.keys.push(key.to_string());
        self.cells.push(cell(value)?);
        Ok(())
    }
    fn end(self) -> Result<(), NotFlat> {
        Ok(())
    }
}

impl ser::SerializeMap for &mut Row {
    type Ok = ();
    type Error = NotFlat;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), NotFlat> {
        self.keys.push(cell(key)?);
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NotFlat> {
        self.cells.push(cell(value)?);
        Ok(())
    }
    fn end(self) -> Result<(), NotFlat> {
        Ok(())
    }
}

/// `Err(NotFlat)` for each kind of value that is not a record.
macro_rules! not_flat {
    ($($f:ident($($t:ty),*)),* $(,)?) => {
        $(fn $f(self, $(_: $t),*) -> Result<(), NotFlat> {
            Err(NotFlat)
        })*
    };
}

impl ser::Serializer for &mut Row {
    type Ok = ();
    type Error = NotFlat;
    type SerializeSeq = Impossible<(), NotFlat>;
    type SerializeTuple = Impossible<(), NotFlat>;
    type SerializeTupleStruct = Impossible<(), NotFlat>;
    type SerializeTupleVariant = Impossible<(), NotFlat>;
    type SerializeMap = Self;
    type SerializeStruct = Self;
    type SerializeStructVariant = Impossible<(), NotFlat>;

    not_flat!(
        serialize_bool(bool),
        serialize_i8(i8),
        serialize_i16(i16),
        serialize_i32(i32),
        serialize_i64(i64),
        serialize_u8(u8),
        serialize_u16(u16),
        serialize_u32(u32),
        serialize_u64(u64),
        serialize_f32(f32),
        serialize_f64(f64),
        serialize_char(char),
        serialize_str(&str),
        serialize_bytes(&[u8]),
        serialize_none(),
        serialize_unit(),
        serialize_unit_struct(&'static str),
        serialize_unit_variant(&'static str, u32, &'static str),
    );

    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), NotFlat> {
        value.serialize(self)
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        value: &T,
    ) -> Result<(), NotFlat> {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &T,
    ) -> Result<(), NotFlat> {
        Err(NotFlat)
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Self::SerializeSeq, NotFlat> {
        Err(NotFlat)
    }
    fn serialize_tuple(self, _: usize) -> Result<Self::SerializeTuple, NotFlat> {
        Err(NotFlat)
    }
    fn serialize_tuple_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleStruct, NotFlat> {
        Err(NotFlat)
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleVariant, NotFlat> {
        Err(NotFlat)
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Self, NotFlat> {
        Ok(self)
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Self, NotFlat> {
        Ok(self)
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStructVariant, NotFlat> {
        Err(NotFlat)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Serialize;

    #[derive(Serialize)]
    struct Part {
        e: Vec<u8>,
        f: &'static str,
    }

    #[derive(Serialize)]
    struct Row {
        a: f64,
        b: Option<f64>,
        c: String,
        d: bool,
        #[serde(flatten)]
        part: Option<Part>,
    }

    #[test]
    fn writes_the_header_once_flattened_parts_and_empty_cells_for_absent_values() {
        let rows = [
            Row {
                a: 1.5,
                b: None,
                c: "inner".into(),
                d: true,
                part: Some(Part {
                    e: vec![1, 2],
                    f: "x \"y\"",
                }),
            },
            Row {
                a: 1e-7,
                b: Some(f64::NAN),
                c: "outer".into(),
                d: false,
                part: Some(Part { e: vec![], f: "" }),
            },
        ];
        assert_eq!(
            csv(&rows),
            "a,b,c,d,e,f\n1.5,,inner,true,[1,2],x \"y\"\n1e-7,,outer,false,[],\n"
        );
        assert_eq!(csv::<Row>(&[]), "");
        assert_eq!(csv(&[1.0, 2.0]), "", "numbers are not records");
    }
}
