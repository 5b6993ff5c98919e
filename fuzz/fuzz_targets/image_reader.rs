//! `vivae drive-image`'s PNG reader on arbitrary bytes: it refuses or
//! decodes; an image whose header claims more than
//! `vivae_lab::export::image::MAX_IMAGE_PIXELS` pixels is refused before
//! anything is allocated for it, and none panics.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(image) = vivae_lab::export::image::Image::from_png(data, "fuzz.png") {
        assert!((image.width * image.height) as u64 <= vivae_lab::export::image::MAX_IMAGE_PIXELS);
        assert_eq!(image.rgba.len(), image.width * image.height * 4);
    }
});
