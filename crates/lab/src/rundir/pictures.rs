//! A champion's episode as rendered pictures (`film.json`), written into
//! the run directory by a host that plays the task's episodes itself (the
//! Python package, from Gymnasium's `render_mode="rgb_array"`): the program
//! cannot play them, so report.html animates these frames instead of a
//! film it draws. [`read`] checks the file before the page embeds it.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// The file's name in a run directory.
pub const FILE: &str = "film.json";

/// The prefix of every frame's image: a PNG as a data URL.
pub const IMAGE_PREFIX: &str = "data:image/png;base64,";

/// At most this many frames (a page shows a few hundred).
pub const MAX_FRAMES: usize = 5000;

/// At most this many pixels a side.
pub const MAX_SIDE: u32 = 2048;

/// The file as the host writes it.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pictures {
    /// The environment the episode was played in.
    pub env: String,
    /// The environment's seed of the episode.
    pub seed: u64,
    /// The champion's generation.
    pub generation: u32,
    /// The champion's fitness.
    pub fitness: f64,
    /// Width of every frame, in pixels.
    pub width: u32,
    /// Height of every frame, in pixels.
    pub height: u32,
    /// Environment steps between two frames.
    pub every: u32,
    /// The episode's steps.
    pub steps: u32,
    /// The episode's return.
    #[serde(rename = "return")]
    pub total: f64,
    /// The frames, in order.
    pub frames: Vec<Picture>,
}

/// One frame as the host writes it.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Picture {
    /// The step it shows (from 0).
    pub step: u32,
    /// The reward of the steps since the previous frame (so the frames'
    /// rewards sum to the return).
    pub reward: f64,
    /// The picture, a PNG data URL ([`IMAGE_PREFIX`]).
    pub image: String,
}

/// The frames as report.html's film player reads any film: the box shown
/// (the picture's pixels), no backdrop, one episode's frames each with its
/// image and no shapes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reel {
    /// Left, bottom, right, top: the picture's pixels.
    pub view: [f64; 4],
    /// Nothing stays still behind the pictures.
    pub backdrop: [(); 0],
    /// The frames.
    pub frames: Vec<ReelFrame>,
}

/// A frame of a [`Reel`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReelFrame {
    /// Always episode 0: the film holds one.
    pub episode: u32,
    /// No shapes: the picture is the frame.
    pub shapes: [(); 0],
    /// The step, reward and image.
    #[serde(flatten)]
    pub picture: Picture,
}

impl Pictures {
    /// The frames as the film player reads them.
    pub fn reel(&self) -> Reel {
        Reel {
            view: [0.0, 0.0, f64::from(self.width), f64::from(self.height)],
            backdrop: [],
            frames: (self.frames.iter())
                .map(|p| ReelFrame {
                    episode: 0,
                    shapes: [],
                    picture: p.clone(),
                })
                .collect(),
        }
    }

    /// Whether it makes sense: a reason naming what does not.
    fn check(&self) -> std::result::Result<(), String> {
        if self.width == 0 || self.height == 0 || self.width > MAX_SIDE || self.height > MAX_SIDE {
            return Err(format!(
                "frames of {} x {} pixels: each side must be 1 to {MAX_SIDE}",
                self.width, self.height
            ));
        }
        if self.frames.is_empty() || self.frames.len() > MAX_FRAMES {
            return Err(format!(
                "{} frames: expected 1 to {MAX_FRAMES}",
                self.frames.len()
            ));
        }
        if self.every == 0 {
            return Err("every = 0: frames must be at least one step apart".into());
        }
        if !self.total.is_finite() || !self.fitness.is_finite() {
            return Err("a return or fitness that is not a finite number".into());
        }
        for (k, p) in self.frames.iter().enumerate() {
            let Some(data) = p.image.strip_prefix(IMAGE_PREFIX) else {
                return Err(format!(
                    "frames[{k}].image: not a PNG data URL ({IMAGE_PREFIX}…)"
                ));
            };
            // Base64 only: the page puts it in an image's source as it is.
            if let Some(c) = data
                .chars()
                .find(|c| !(c.is_ascii_alphanumeric() || matches!(c, '+' | '/' | '=')))
            {
                return Err(format!("frames[{k}].image: {c:?} is not base64"));
            }
            if !p.reward.is_finite() {
                return Err(format!("frames[{k}].reward: not a finite number"));
            }
            if k > 0 && p.step <= self.frames[k - 1].step {
                return Err(format!(
                    "frames[{k}].step: {} does not follow {}",
                    p.step,
                    self.frames[k - 1].step
                ));
            }
        }
        Ok(())
    }
}

/// The pictures in `dir` ([`FILE`]); none when the host wrote none. A
/// damaged file is refused, naming it and what is wrong.
pub fn read(dir: &Path) -> Result<Option<Pictures>> {
    let path = dir.join(FILE);
    if !path.exists() {
        return Ok(None);
    }
    let text = crate::io::read_text(&path)?;
    let refused = |reason: String| Error::RunFile {
        path: path.clone(),
        reason,
    };
    let pictures: Pictures = serde_json::from_str(&text).map_err(|e| refused(e.to_string()))?;
    pictures.check().map_err(refused)?;
    Ok(Some(pictures))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn written(name: &str, text: &str) -> Result<Option<Pictures>> {
        let dir = super::super::tests::scratch(name);
        std::fs::write(dir.join(FILE), text).unwrap();
        let out = read(&dir);
        std::fs::remove_dir_all(&dir).unwrap();
        out
    }

    fn file(image: &str, step: u32) -> String {
        format!(
            r#"{{"env":"E-v1","seed":0,"generation":3,"fitness":1.5,"width":4,"height":2,"every":2,"steps":3,"return":2.5,
               "frames":[{{"step":0,"reward":0.0,"image":"{IMAGE_PREFIX}iVBORw0KGgo="}},{{"step":{step},"reward":2.5,"image":"{image}"}}]}}"#
        )
    }

    #[test]
    fn a_host_written_film_reads_as_a_reel_of_its_frames() {
        let p = written("pictures-good", &file(&format!("{IMAGE_PREFIX}AAAA"), 2))
            .unwrap()
            .unwrap();
        let reel = serde_json::to_value(p.reel()).unwrap();
        assert_eq!(reel["view"], serde_json::json!([0.0, 0.0, 4.0, 2.0]));
        assert_eq!(reel["frames"][1]["step"], 2);
        assert_eq!(reel["frames"][1]["reward"], 2.5);
        assert_eq!(reel["frames"][1]["episode"], 0);
        assert_eq!(reel["frames"][1]["shapes"], serde_json::json!([]));
        assert_eq!(reel["frames"][1]["image"], format!("{IMAGE_PREFIX}AAAA"));
        assert_eq!(reel["backdrop"], serde_json::json!([]));
    }

    #[test]
    fn no_file_is_no_film_and_a_damaged_one_is_refused_by_name() {
        let dir = super::super::tests::scratch("pictures-none");
        assert_eq!(read(&dir).unwrap(), None);
        std::fs::remove_dir_all(&dir).unwrap();
        for (image, step, says) in [
            ("javascript:alert(1)", 2, "not a PNG data URL"),
            (&format!("{IMAGE_PREFIX}AA</script>"), 2, "is not base64"),
            (&format!("{IMAGE_PREFIX}AAAA"), 0, "does not follow 0"),
        ] {
            let e = written("pictures-bad", &file(image, step)).unwrap_err();
            assert!(
                e.to_string().contains(FILE) && e.to_string().contains(says),
                "{e}"
            );
            assert!(e.is_bad_input(), "{e:?}");
        }
        let e = written("pictures-bad", "{\"env\": 1}").unwrap_err();
        assert!(e.to_string().contains(FILE), "{e}");
    }
}
