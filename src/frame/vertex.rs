//! Vertex data of a draw: object-space positions and the attributes the program gave, each
//! either one value shared by every vertex or one value per vertex (structure of arrays).

/// One attribute of a draw's vertices. `values` holds either one value, shared by every
/// vertex, or exactly one value per vertex; it is empty only when there is no vertex. A batch
/// whose colour never changes therefore carries one colour, not one per vertex.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Attrib<T> {
    /// One shared value, or one value per vertex.
    pub values: Vec<T>,
}

impl<T: Copy + PartialEq> Attrib<T> {
    /// The value of vertex `i`; `None` when there is no value at all.
    pub fn get(&self, i: usize) -> Option<T> {
        match self.values.len() {
            1 => Some(self.values[0]),
            _ => self.values.get(i).copied(),
        }
    }

    /// Whether one value serves every vertex.
    pub fn is_constant(&self) -> bool {
        self.values.len() == 1
    }

    /// Appends the value of vertex number `count` (the vertices before it number `count`):
    /// stays shared while the value does not change. No allocation once the storage has grown.
    #[inline]
    pub fn push(&mut self, value: T, count: usize) {
        if count == 0 {
            self.values.clear();
            self.values.push(value);
        } else if self.values.len() == 1 && count > 0 {
            let first = self.values[0];
            if first != value {
                if count > 1 {
                    self.values.resize(count, first);
                }
                self.values.push(value);
            }
        } else {
            self.values.push(value);
        }
    }

    /// Appends the `other_count` vertices of `other` after this attribute's `count` vertices.
    pub fn append(&mut self, count: usize, other: &Attrib<T>, other_count: usize) {
        if other_count == 0 {
            return;
        }
        if count == 0 {
            self.values.clear();
            self.values.extend_from_slice(&other.values);
            return;
        }
        if self.is_constant() && other.is_constant() && self.values[0] == other.values[0] {
            return;
        }
        self.expand(count);
        if other.is_constant() {
            let v = other.values[0];
            self.values.resize(count + other_count, v);
        } else {
            self.values.extend_from_slice(&other.values[..other_count.min(other.values.len())]);
        }
    }

    /// The values of the vertices from `from` on: the shared value stays shared.
    pub fn tail(&self, from: usize) -> Attrib<T> {
        match self.values.len() {
            1 => self.clone(),
            _ => Attrib { values: self.values.get(from..).unwrap_or_default().to_vec() },
        }
    }

    /// Stores one value per vertex for `count` vertices.
    pub fn expand(&mut self, count: usize) {
        if self.values.len() == 1 && count > 1 {
            let v = self.values[0];
            self.values.resize(count, v);
        }
    }

    /// Keeps the first `count` vertices.
    pub fn truncate(&mut self, count: usize) {
        if !self.is_constant() || count == 0 {
            self.values.truncate(count);
        }
    }

    /// Sets one value for every vertex.
    pub fn set_constant(&mut self, value: T) {
        self.values.clear();
        self.values.push(value);
    }
}

/// The vertices of a draw (or of a batch being assembled), in object space.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Vertices {
    /// Object-space positions `(x, y, z, w)`, one per vertex.
    pub position: Vec<[f32; 4]>,
    /// Normals.
    pub normal: Attrib<[f32; 3]>,
    /// Primary colours (RGBA).
    pub color: Attrib<[f32; 4]>,
    /// Secondary colours (RGB).
    pub secondary_color: Attrib<[f32; 3]>,
    /// Texture coordinates `(s, t, r, q)` of each texture unit.
    pub texcoords: Vec<Attrib<[f32; 4]>>,
    /// Fog coordinates.
    pub fog_coord: Attrib<f32>,
    /// Colour indices (colour-index mode).
    pub color_index: Attrib<f32>,
    /// Generic vertex attributes (OpenGL 2.0 section 2.7) by index; index 0 is the position
    /// and stays empty here. Only draws that run a program read them.
    pub generic: Vec<Attrib<[f32; 4]>>,
}

impl Vertices {
    /// Vertices with storage for the attributes of `units` texture units.
    pub fn with_units(units: usize) -> Vertices {
        Vertices { texcoords: vec![Attrib::default(); units], ..Vertices::default() }
    }

    /// Number of vertices.
    pub fn len(&self) -> usize {
        self.position.len()
    }

    /// Whether there is no vertex.
    pub fn is_empty(&self) -> bool {
        self.position.is_empty()
    }

    /// Removes every vertex, keeping the storage.
    pub fn clear(&mut self) {
        self.truncate(0);
    }

    /// Keeps the first `count` vertices.
    pub fn truncate(&mut self, count: usize) {
        self.position.truncate(count);
        self.normal.truncate(count);
        self.color.truncate(count);
        self.secondary_color.truncate(count);
        for t in &mut self.texcoords {
            t.truncate(count);
        }
        self.fog_coord.truncate(count);
        self.color_index.truncate(count);
        for g in &mut self.generic {
            g.truncate(count);
        }
    }

    /// The vertices from `from` on (none when `from` is past the last), each attribute
    /// copied over that range only.
    pub fn tail(&self, from: usize) -> Vertices {
        let from = from.min(self.len());
        Vertices {
            position: self.position[from..].to_vec(),
            normal: self.normal.tail(from),
            color: self.color.tail(from),
            secondary_color: self.secondary_color.tail(from),
            texcoords: self.texcoords.iter().map(|t| t.tail(from)).collect(),
            fog_coord: self.fog_coord.tail(from),
            color_index: self.color_index.tail(from),
            generic: self.generic.iter().map(|g| g.tail(from)).collect(),
        }
    }

    /// Appends every vertex of `other`. Into no vertex, the result equals `other` (the storage
    /// of texture units and generic attributes `other` lacks is dropped, the rest reused).
    pub fn append(&mut self, other: &Vertices) {
        let (n, m) = (self.len(), other.len());
        if n == 0 {
            self.texcoords.truncate(other.texcoords.len());
            self.generic.truncate(other.generic.len());
        }
        self.position.extend_from_slice(&other.position);
        self.normal.append(n, &other.normal, m);
        self.color.append(n, &other.color, m);
        self.secondary_color.append(n, &other.secondary_color, m);
        if self.texcoords.len() < other.texcoords.len() {
            // Units these vertices lacked had the initial coordinates (0, 0, 0, 1).
            let initial = Attrib { values: if n == 0 { Vec::new() } else { vec![[0.0, 0.0, 0.0, 1.0]] } };
            self.texcoords.resize(other.texcoords.len(), initial);
        }
        for (t, o) in self.texcoords.iter_mut().zip(&other.texcoords) {
            t.append(n, o, m);
        }
        self.fog_coord.append(n, &other.fog_coord, m);
        self.color_index.append(n, &other.color_index, m);
        if self.generic.len() < other.generic.len() {
            // Generic attributes these vertices lacked had the initial value (0, 0, 0, 1).
            let initial = Attrib { values: if n == 0 { Vec::new() } else { vec![[0.0, 0.0, 0.0, 1.0]] } };
            self.generic.resize(other.generic.len(), initial);
        }
        for (g, o) in self.generic.iter_mut().zip(&other.generic) {
            g.append(n, o, m);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Attrib, Vertices};

    #[test]
    fn attrib_stays_shared_until_it_changes() {
        let mut a = Attrib::default();
        a.push(1.0f32, 0);
        a.push(1.0, 1);
        a.push(1.0, 2);
        assert_eq!(a.values, vec![1.0]);
        a.push(2.0, 3);
        assert_eq!(a.values, vec![1.0, 1.0, 1.0, 2.0]);
        assert_eq!(a.get(3), Some(2.0));
        let mut b = Attrib::default();
        b.push(5.0f32, 0);
        a.append(4, &b, 2);
        assert_eq!(a.values, vec![1.0, 1.0, 1.0, 2.0, 5.0, 5.0]);
        let mut c = Attrib::default();
        c.push(5.0f32, 0);
        c.append(3, &b, 2);
        assert_eq!(c.values, vec![5.0], "equal shared values stay shared");
    }

    #[test]
    fn vertices_append_fills_missing_units() {
        let mut a = Vertices::with_units(0);
        a.position.push([0.0; 4]);
        let mut b = Vertices::with_units(1);
        b.position.push([1.0; 4]);
        b.texcoords[0].push([5.0, 0.0, 0.0, 1.0], 0);
        a.append(&b);
        assert_eq!(a.texcoords[0].values, vec![[0.0, 0.0, 0.0, 1.0], [5.0, 0.0, 0.0, 1.0]]);
    }

    #[test]
    fn a_tail_holds_the_last_vertices_and_keeps_shared_values_shared() {
        let mut v = Vertices::with_units(2);
        for i in 0..5 {
            v.position.push([i as f32; 4]);
            v.color.push([0.5; 4], i);
            v.texcoords[1].push([i as f32 * 2.0; 4], i);
        }
        let tail = v.tail(3);
        assert_eq!(tail.position, vec![[3.0; 4], [4.0; 4]]);
        assert_eq!(tail.color.values, vec![[0.5; 4]], "shared");
        assert_eq!(tail.texcoords[1].values, vec![[6.0; 4], [8.0; 4]]);
        assert!(tail.texcoords[0].values.is_empty() && tail.normal.values.is_empty());
        for i in 0..2 {
            assert_eq!(tail.texcoords[1].get(i), v.texcoords[1].get(3 + i));
            assert_eq!(tail.color.get(i), v.color.get(3 + i));
        }
        assert_eq!(v.tail(0), v);
        assert!(v.tail(9).is_empty());
    }

    #[test]
    fn appending_into_emptied_storage_equals_the_appended_vertices() {
        let mut used = Vertices::with_units(4);
        used.generic = vec![Attrib::default(); 3];
        for i in 0..100 {
            used.position.push([i as f32; 4]);
            used.texcoords[3].push([i as f32; 4], i);
            used.generic[2].push([1.0; 4], i);
        }
        let capacity = used.position.capacity();
        used.clear();
        let mut b = Vertices::with_units(2);
        b.position.push([1.0; 4]);
        b.color.push([0.5; 4], 0);
        used.append(&b);
        assert_eq!(used, b, "units and generic attributes b lacks are gone");
        assert_eq!(used.position.capacity(), capacity, "the storage is reused");
    }
}
