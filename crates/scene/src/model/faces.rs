//! The faces of a [`super::Shape::Mesh`], stored flat: every face's vertex indices one after
//! another in one `Vec<u32>`, and where each face ends in another.
//!
//! Invariants: `ends` is non-decreasing and its last entry (if any) is `indices.len()`, so
//! face `i` is `indices[ends[i - 1]..ends[i]]` (from 0 for the first); a mesh costs 4 bytes
//! per index and 4 per face, with no allocation per face. In RON the faces read and write
//! exactly as a list of lists (`faces: [[0, 1, 2, 3], [3, 2, 4]]`), through the same serde
//! calls a `Vec<Vec<u32>>` makes, so files, messages and error positions are those of one.

use std::fmt;
use std::iter::FusedIterator;
use std::ops::{Index, IndexMut, Range};

use serde::de::{DeserializeSeed, Deserializer, SeqAccess, Visitor};
use serde::ser::{SerializeSeq, Serializer};
use serde::{Deserialize, Serialize};

/// The faces of a polygon mesh: a list of faces, each a list of indices into the mesh's
/// points, held in two flat vectors.
///
/// Built with [`Faces::push`], collected from faces (`[u32; N]`, `&[u32]`, `Vec<u32>`), or
/// converted from a `Vec<Vec<u32>>`; read like a slice of faces ([`Faces::len`],
/// [`Faces::iter`], `faces[i]`, [`Faces::get`]).
///
/// ```
/// use reyes_scene::Faces;
///
/// let mut faces = Faces::from(vec![vec![0, 1, 2, 3]]);
/// faces.push(&[3, 2, 4]);
/// assert_eq!(faces.len(), 2);
/// assert_eq!(&faces[1], &[3, 2, 4]);
/// assert_eq!(format!("{faces:?}"), "[[0, 1, 2, 3], [3, 2, 4]]");
/// ```
///
/// # Panics
///
/// Adding faces beyond `u32::MAX` indices in all (16 GiB of indices) panics; reading a scene
/// with that many is an error instead.
#[derive(Clone, Default, PartialEq, Eq, Hash)]
pub struct Faces {
    /// Where each face ends in `indices` (one past its last index).
    ends: Vec<u32>,
    /// The indices of every face, face after face.
    indices: Vec<u32>,
}

/// The panic message of a mesh with more indices than a `u32` counts.
const TOO_MANY: &str = "a mesh holds at most u32::MAX face indices";

impl Faces {
    /// No faces.
    pub const fn new() -> Faces {
        Faces { ends: Vec::new(), indices: Vec::new() }
    }

    /// No faces, with room for `faces` faces of `indices` indices in all.
    pub fn with_capacity(faces: usize, indices: usize) -> Faces {
        Faces { ends: Vec::with_capacity(faces), indices: Vec::with_capacity(indices) }
    }

    /// The number of faces.
    pub fn len(&self) -> usize {
        self.ends.len()
    }

    /// True if there are no faces.
    pub fn is_empty(&self) -> bool {
        self.ends.is_empty()
    }

    /// Every face's indices, face after face (the sum of the faces' lengths).
    pub fn indices(&self) -> &[u32] {
        &self.indices
    }

    /// Every face's indices, mutable (which faces they make up stays fixed).
    pub fn indices_mut(&mut self) -> &mut [u32] {
        &mut self.indices
    }

    /// Face `i`'s indices, or `None` if there are not that many faces.
    pub fn get(&self, i: usize) -> Option<&[u32]> {
        let range = self.range(i)?;
        self.indices.get(range)
    }

    /// Face `i`'s indices, mutable, or `None` if there are not that many faces.
    pub fn get_mut(&mut self, i: usize) -> Option<&mut [u32]> {
        let range = self.range(i)?;
        self.indices.get_mut(range)
    }

    /// The faces in order.
    pub fn iter(&self) -> FaceIter<'_> {
        FaceIter { faces: self, front: 0, back: self.len() }
    }

    /// Appends the face `face` (any number of indices, none included).
    ///
    /// # Panics
    ///
    /// If the faces would hold more than `u32::MAX` indices in all.
    pub fn push(&mut self, face: &[u32]) {
        self.indices.extend_from_slice(face);
        self.close_face();
    }

    /// Appends the face whose indices `face` yields, without a slice to copy from.
    ///
    /// # Panics
    ///
    /// If the faces would hold more than `u32::MAX` indices in all.
    pub fn push_iter(&mut self, face: impl IntoIterator<Item = u32>) {
        self.indices.extend(face);
        self.close_face();
    }

    /// Removes every face, keeping the allocations.
    pub fn clear(&mut self) {
        self.ends.clear();
        self.indices.clear();
    }

    /// Where face `i` lies in `indices`.
    fn range(&self, i: usize) -> Option<Range<usize>> {
        let end = *self.ends.get(i)? as usize;
        let start = match i.checked_sub(1) {
            Some(j) => self.ends[j] as usize,
            None => 0,
        };
        Some(start..end)
    }

    /// Ends a face after the indices appended since the last one ended.
    fn close_face(&mut self) {
        let end = u32::try_from(self.indices.len()).expect(TOO_MANY);
        self.ends.push(end);
    }
}

impl Index<usize> for Faces {
    type Output = [u32];

    /// Face `i`'s indices.
    ///
    /// # Panics
    ///
    /// If `i >= self.len()`.
    fn index(&self, i: usize) -> &[u32] {
        match self.range(i) {
            Some(range) => &self.indices[range],
            None => panic!("face index {i} out of range for {} faces", self.len()),
        }
    }
}

impl IndexMut<usize> for Faces {
    /// Face `i`'s indices, mutable.
    ///
    /// # Panics
    ///
    /// If `i >= self.len()`.
    fn index_mut(&mut self, i: usize) -> &mut [u32] {
        match self.range(i) {
            Some(range) => &mut self.indices[range],
            None => panic!("face index {i} out of range for {} faces", self.len()),
        }
    }
}

/// The faces of a [`Faces`] in order, as slices of indices (see [`Faces::iter`]).
#[derive(Debug, Clone)]
pub struct FaceIter<'a> {
    faces: &'a Faces,
    /// The next face from the front.
    front: usize,
    /// One past the next face from the back.
    back: usize,
}

impl<'a> Iterator for FaceIter<'a> {
    type Item = &'a [u32];

    fn next(&mut self) -> Option<&'a [u32]> {
        if self.front >= self.back {
            return None;
        }
        let face = self.faces.get(self.front);
        self.front += 1;
        face
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.back - self.front;
        (n, Some(n))
    }
}

impl DoubleEndedIterator for FaceIter<'_> {
    fn next_back(&mut self) -> Option<Self::Item> {
        if self.front >= self.back {
            return None;
        }
        self.back -= 1;
        self.faces.get(self.back)
    }
}

impl ExactSizeIterator for FaceIter<'_> {}

impl FusedIterator for FaceIter<'_> {}

impl<'a> IntoIterator for &'a Faces {
    type Item = &'a [u32];
    type IntoIter = FaceIter<'a>;

    fn into_iter(self) -> FaceIter<'a> {
        self.iter()
    }
}

impl<F: AsRef<[u32]>> Extend<F> for Faces {
    fn extend<I: IntoIterator<Item = F>>(&mut self, faces: I) {
        for face in faces {
            self.push(face.as_ref());
        }
    }
}

impl<F: AsRef<[u32]>> FromIterator<F> for Faces {
    fn from_iter<I: IntoIterator<Item = F>>(faces: I) -> Faces {
        let mut out = Faces::new();
        out.extend(faces);
        out
    }
}

impl From<Vec<Vec<u32>>> for Faces {
    fn from(faces: Vec<Vec<u32>>) -> Faces {
        let total = faces.iter().map(Vec::len).sum();
        let mut out = Faces::with_capacity(faces.len(), total);
        out.extend(faces);
        out
    }
}

impl From<&[Vec<u32>]> for Faces {
    fn from(faces: &[Vec<u32>]) -> Faces {
        faces.iter().collect()
    }
}

impl<const N: usize> From<&[[u32; N]]> for Faces {
    fn from(faces: &[[u32; N]]) -> Faces {
        faces.iter().collect()
    }
}

impl From<&Faces> for Vec<Vec<u32>> {
    fn from(faces: &Faces) -> Vec<Vec<u32>> {
        faces.iter().map(<[u32]>::to_vec).collect()
    }
}

/// Printed as the list of lists it stands for: `[[0, 1, 2], [2, 1, 3]]`.
impl fmt::Debug for Faces {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// Written as a sequence of sequences of `u32`, as a `Vec<Vec<u32>>` is.
impl Serialize for Faces {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut seq = serializer.serialize_seq(Some(self.len()))?;
        for face in self {
            seq.serialize_element(face)?;
        }
        seq.end()
    }
}

/// Read as a sequence of sequences of `u32` with the calls a `Vec<Vec<u32>>` makes (so a
/// format reports the same errors at the same places), each face's indices appended to the
/// flat storage as they are read.
impl<'de> Deserialize<'de> for Faces {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Faces, D::Error> {
        deserializer.deserialize_seq(FacesVisitor)
    }
}

/// What serde expects where a list is missing, as for a `Vec`.
const EXPECTING: &str = "a sequence";

/// Reads the outer list: the faces.
struct FacesVisitor;

impl<'de> Visitor<'de> for FacesVisitor {
    type Value = Faces;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(EXPECTING)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Faces, A::Error> {
        // Room for the announced faces (bounded, as serde bounds a `Vec`'s preallocation).
        let faces = seq.size_hint().unwrap_or(0).min(1 << 16);
        let mut out = Faces::with_capacity(faces, 4 * faces);
        while seq.next_element_seed(FaceSeed(&mut out))?.is_some() {}
        Ok(out)
    }
}

/// Reads one inner list, a face, onto the end of the faces.
struct FaceSeed<'a>(&'a mut Faces);

impl<'de> DeserializeSeed<'de> for FaceSeed<'_> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<(), D::Error> {
        deserializer.deserialize_seq(self)
    }
}

impl<'de> Visitor<'de> for FaceSeed<'_> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(EXPECTING)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
        let faces = self.0;
        while let Some(index) = seq.next_element::<u32>()? {
            faces.indices.push(index);
        }
        if u32::try_from(faces.indices.len()).is_err() {
            return Err(serde::de::Error::custom(TOO_MANY));
        }
        faces.close_face();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Faces {
        Faces::from(vec![vec![0, 1, 2, 3], vec![3, 2, 4], vec![], vec![5, 6, 7]])
    }

    #[test]
    fn faces_read_back_as_pushed() {
        let f = sample();
        assert_eq!(f.len(), 4);
        assert!(!f.is_empty() && Faces::new().is_empty());
        assert_eq!(&f[0], &[0, 1, 2, 3]);
        assert_eq!(&f[1], &[3, 2, 4]);
        assert!(f[2].is_empty());
        assert_eq!(f.get(3), Some(&[5, 6, 7][..]));
        assert_eq!(f.get(4), None);
        assert_eq!(f.indices(), &[0, 1, 2, 3, 3, 2, 4, 5, 6, 7]);
        assert_eq!(
            Vec::<Vec<u32>>::from(&f),
            vec![vec![0, 1, 2, 3], vec![3, 2, 4], vec![], vec![5, 6, 7]]
        );
    }

    #[test]
    fn iteration_runs_both_ways_with_an_exact_length() {
        let f = sample();
        let mut it = f.iter();
        assert_eq!(it.len(), 4);
        assert_eq!(it.next(), Some(&[0, 1, 2, 3][..]));
        assert_eq!(it.next_back(), Some(&[5, 6, 7][..]));
        assert_eq!(it.len(), 2);
        assert_eq!(it.next_back(), Some(&[][..]));
        assert_eq!(it.next(), Some(&[3, 2, 4][..]));
        assert_eq!((it.next(), it.next_back(), it.len()), (None, None, 0));
        let reversed: Vec<&[u32]> = f.iter().rev().collect();
        assert_eq!(reversed.len(), 4);
        assert_eq!(reversed[0], &[5, 6, 7]);
    }

    #[test]
    fn collected_and_converted_faces_agree() {
        let f = sample();
        let from_slices: Faces = f.iter().collect();
        let from_vecs: Faces = Vec::<Vec<u32>>::from(&f).into_iter().collect();
        assert_eq!(from_slices, f);
        assert_eq!(from_vecs, f);
        assert_eq!(
            Faces::from(&[[0u32, 1, 2], [2, 1, 3]][..]),
            Faces::from(vec![vec![0, 1, 2], vec![2, 1, 3]])
        );
        assert_ne!(Faces::from(vec![vec![0, 1], vec![2]]), Faces::from(vec![vec![0], vec![1, 2]]));
    }

    #[test]
    fn faces_edit_in_place() {
        let mut f = sample();
        f[1][0] = 9;
        if let Some(face) = f.get_mut(3) {
            face.reverse();
        }
        f.indices_mut()[0] = 8;
        f.push_iter((10..13).rev());
        assert_eq!(format!("{f:?}"), "[[8, 1, 2, 3], [9, 2, 4], [], [7, 6, 5], [12, 11, 10]]");
        f.clear();
        assert!(f.is_empty() && f.indices().is_empty());
    }

    #[test]
    fn debug_prints_a_list_of_lists() {
        let f = sample();
        let nested = Vec::<Vec<u32>>::from(&f);
        assert_eq!(format!("{f:?}"), format!("{nested:?}"));
        assert_eq!(format!("{f:#?}"), format!("{nested:#?}"));
    }

    #[test]
    fn ron_reads_and_writes_a_list_of_lists() {
        let f = sample();
        let nested = Vec::<Vec<u32>>::from(&f);
        let text = ron::to_string(&f).expect("faces serialise");
        assert_eq!(text, ron::to_string(&nested).expect("lists serialise"));
        assert_eq!(text, "[[0,1,2,3],[3,2,4],[],[5,6,7]]");
        let back: Faces = ron::from_str(&text).expect("faces read back");
        assert_eq!(back, f);
        for bad in ["[[0, -1]]", "[[0, 1.5]]", "[0, 1]", "5", "[[0, 1], 2]", "[[0 1]]", "[[0]"] {
            let flat = ron::from_str::<Faces>(bad).map(|f| Vec::<Vec<u32>>::from(&f));
            let nested = ron::from_str::<Vec<Vec<u32>>>(bad);
            assert_eq!(flat, nested, "{bad}");
        }
    }

    #[test]
    #[should_panic(expected = "face index 4 out of range for 4 faces")]
    fn indexing_past_the_end_panics() {
        let _ = &sample()[4];
    }
}
