//! Reading the JSON documents a user hands in (scenes, taught demonstrations, episode logs) with
//! errors that say where: the path of the offending value, what was expected, and the line and
//! column — `steps[3].pose[1]: invalid type: string "x", expected f64 at line 12 column 7`.

use serde::de::DeserializeOwned;

use super::{SceneError, World};

/// A JSON document that does not parse into the expected type.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct JsonError {
    /// The path of the value at fault (`steps[3].pose[1]`); empty for the document itself.
    pub path: String,
    /// What is wrong (serde's words, without the location).
    pub message: String,
    /// Line of the fault (1-based).
    pub line: usize,
    /// Column of the fault (1-based).
    pub column: usize,
}

impl JsonError {
    /// `line L column C`.
    pub fn location(&self) -> String {
        format!("line {} column {}", self.line, self.column)
    }

    /// The message with its location: `invalid type: … at line L column C`.
    pub fn located_message(&self) -> String {
        format!("{} at {}", self.message, self.location())
    }

    /// Where and what, for errors of the form `{where}: {what}`: the path and the located message,
    /// or (for the document itself) the location and the message.
    pub fn into_parts(self) -> (String, String) {
        if self.path.is_empty() {
            (self.location(), self.message)
        } else {
            let what = self.located_message();
            (self.path, what)
        }
    }
}

impl std::fmt::Display for JsonError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.path.is_empty() {
            write!(f, "{}", self.located_message())
        } else {
            write!(f, "{}: {}", self.path, self.located_message())
        }
    }
}

impl std::error::Error for JsonError {}

/// Parses `text` as a `T`; an error names the path of the value at fault (see [`JsonError`]).
///
/// The page's first-load wasm module (cfg `first_load`) reads only the documents embedded in it
/// (the page loads users' files on the full module), so there errors carry the line and column
/// but no path: path tracking would add its own copy of every reader, 15 KB gzipped.
pub fn parse_json<T: DeserializeOwned>(text: &str) -> Result<T, JsonError> {
    let mut de = serde_json::Deserializer::from_str(text);
    #[cfg(not(first_load))]
    let value = serde_path_to_error::deserialize(&mut de).map_err(|e| {
        let path = e.path().to_string();
        json_error(if path == "." { String::new() } else { path }, e.inner())
    })?;
    #[cfg(first_load)]
    let value = T::deserialize(&mut de).map_err(|e| json_error(String::new(), &e))?;
    // Anything but white space after the document is an error too.
    de.end().map_err(|e| json_error(String::new(), &e))?;
    Ok(value)
}

fn json_error(path: String, e: &serde_json::Error) -> JsonError {
    let full = e.to_string();
    let suffix = format!(" at line {} column {}", e.line(), e.column());
    JsonError {
        path,
        message: full.strip_suffix(&suffix).unwrap_or(&full).to_string(),
        line: e.line(),
        column: e.column(),
    }
}

/// A world from scene JSON (a `WorldSnapshot`), as [`World::from_json`] reads it, but a value of
/// the wrong type is named by its path: `bodies[2].pose.position[1]: invalid type: …`.
pub fn world_from_json(text: &str) -> Result<World, SceneError> {
    let snapshot = parse_json(text).map_err(|e| {
        let (path, message) = e.into_parts();
        SceneError { path, message }
    })?;
    World::from_snapshot(&snapshot)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Deserialize)]
    #[allow(dead_code)]
    struct Step {
        pose: [f64; 3],
    }

    #[derive(Debug, Deserialize)]
    #[allow(dead_code)]
    struct Demo {
        steps: Vec<Step>,
    }

    #[test]
    fn a_wrong_type_deep_inside_is_named_by_its_path_and_position() {
        let text = "{\"steps\": [\n  {\"pose\": [0, 0, 0]},\n  {\"pose\": [1, \"x\", 0]}\n]}";
        let e = parse_json::<Demo>(text).unwrap_err();
        assert_eq!(e.path, "steps[1].pose[1]");
        assert_eq!(
            e.to_string(),
            "steps[1].pose[1]: invalid type: string \"x\", expected f64 at line 3 column 18"
        );
    }

    #[test]
    fn malformed_json_names_where_it_stopped() {
        let e = parse_json::<Demo>("{\"steps\": [{\"pose\": [1, 2,]}]}").unwrap_err();
        assert_eq!(e.path, "steps[0].pose");
        assert_eq!((e.line, e.column), (1, 27));
        let e = parse_json::<Demo>("{\"steps\": []} x").unwrap_err();
        assert_eq!(e.to_string(), "trailing characters at line 1 column 15");
    }

    #[test]
    fn a_scene_error_names_the_body_field() {
        let scene = crate::sim::Benchmark::B1.sources().unwrap().scene;
        let mut s: serde_json::Value = serde_json::from_str(&scene).unwrap();
        s["bodies"][2]["pose"]["position"][1] = serde_json::json!("x");
        let e = world_from_json(&serde_json::to_string_pretty(&s).unwrap()).unwrap_err();
        assert_eq!(e.path, "bodies[2].pose.position[1]");
        assert!(
            e.message
                .starts_with("invalid type: string \"x\", expected f64 at line "),
            "{}",
            e.message
        );
    }
}
