//! The few protocol-buffer encodings an ONNX file needs: varints, strings,
//! nested messages and packed scalars (proto2, as `onnx.proto` is).

/// A message being written: fields appended in order.
#[derive(Debug, Default, Clone)]
pub struct Message(Vec<u8>);

impl Message {
    /// An empty message.
    pub fn new() -> Message {
        Message(Vec::new())
    }

    fn varint(&mut self, mut v: u64) {
        while v >= 0x80 {
            self.0.push((v as u8) | 0x80);
            v >>= 7;
        }
        self.0.push(v as u8);
    }

    fn key(&mut self, field: u32, wire: u8) {
        self.varint(u64::from(field) << 3 | u64::from(wire));
    }

    /// A varint field (int32, int64 ≥ 0, enum).
    pub fn int(&mut self, field: u32, v: i64) -> &mut Self {
        self.key(field, 0);
        // Negative values are ten-byte two's complement varints in protobuf.
        self.varint(v as u64);
        self
    }

    /// A length-delimited field: bytes or a string.
    pub fn bytes(&mut self, field: u32, b: &[u8]) -> &mut Self {
        self.key(field, 2);
        self.varint(b.len() as u64);
        self.0.extend_from_slice(b);
        self
    }

    /// A string field.
    pub fn string(&mut self, field: u32, s: &str) -> &mut Self {
        self.bytes(field, s.as_bytes())
    }

    /// A nested message field.
    pub fn message(&mut self, field: u32, m: &Message) -> &mut Self {
        self.bytes(field, &m.0)
    }

    /// The encoded bytes.
    pub fn into_bytes(self) -> Vec<u8> {
        self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn varints_and_nesting_encode_as_protobuf_does() {
        let mut inner = Message::new();
        inner.int(1, 150);
        let mut m = Message::new();
        m.int(1, 1).string(2, "ab").message(3, &inner).int(4, -1);
        let b = m.into_bytes();
        // Protobuf's documented example: field 1 = 150 is 08 96 01.
        assert_eq!(&b[..2], &[0x08, 0x01]);
        assert_eq!(&b[2..6], &[0x12, 2, b'a', b'b']);
        assert_eq!(&b[6..11], &[0x1a, 3, 0x08, 0x96, 0x01]);
        assert_eq!(b[11], 0x20);
        assert_eq!(b.len(), 12 + 10, "a negative int is ten bytes");
    }
}
