//! Matrix recipes: the verifier rebuilds a certificate's matrix itself from
//! parameters stored in the file, rather than trusting a stored matrix.
//!
//! A certificate names a recipe (`{"name": "...", "params": {...}}`); the
//! verifier looks the name up in a [`RecipeRegistry`] and calls
//! [`MatrixRecipe::build`]. Callers register their own recipes (e.g. "rebuild
//! the closed-loop Lyapunov matrix from these wing parameters") with
//! [`RecipeRegistry::register`], either as a type implementing the trait or a
//! plain function pointer wrapped in [`FnRecipe`]. One recipe is built in:
//! [`ExplicitRecipe`] (`"explicit"`), whose params hold the matrix itself.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::certificate::{matrix_from_json, matrix_to_json, CertError};
use crate::matrix::RationalMatrix;

/// Reference to a recipe inside a certificate payload.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RecipeRef {
    /// Registered recipe name, e.g. `"explicit"`.
    pub name: String,
    /// Recipe-specific parameters (rationals as `"p/q"` strings by convention).
    pub params: Value,
}

/// Something that deterministically rebuilds an exact matrix from JSON params.
pub trait MatrixRecipe: Send + Sync {
    /// Unique name under which certificates refer to this recipe.
    fn name(&self) -> &str;
    /// Builds the matrix; `Err` carries a human-readable reason.
    fn build(&self, params: &Value) -> Result<RationalMatrix, String>;
}

/// A recipe given by a name and a plain function pointer.
#[derive(Debug, Clone, Copy)]
pub struct FnRecipe {
    /// Recipe name.
    pub name: &'static str,
    /// The builder.
    pub build: fn(&Value) -> Result<RationalMatrix, String>,
}

impl MatrixRecipe for FnRecipe {
    fn name(&self) -> &str {
        self.name
    }
    fn build(&self, params: &Value) -> Result<RationalMatrix, String> {
        (self.build)(params)
    }
}

/// Built-in recipe `"explicit"`: params `{"rows": [["p/q", …], …]}` hold the
/// matrix verbatim (trusting the file for *which* matrix is meant, but still
/// checking its property exactly).
#[derive(Debug, Clone, Copy, Default)]
pub struct ExplicitRecipe;

/// Name of the built-in [`ExplicitRecipe`].
pub const EXPLICIT: &str = "explicit";

impl MatrixRecipe for ExplicitRecipe {
    fn name(&self) -> &str {
        EXPLICIT
    }
    fn build(&self, params: &Value) -> Result<RationalMatrix, String> {
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Params {
            rows: Vec<Vec<String>>,
        }
        let p: Params = serde_json::from_value(params.clone()).map_err(|e| e.to_string())?;
        matrix_from_json("params.rows", &p.rows).map_err(|e| e.to_string())
    }
}

/// [`RecipeRef`] for the built-in explicit recipe holding `m`.
pub fn explicit_recipe(m: &RationalMatrix) -> RecipeRef {
    RecipeRef { name: EXPLICIT.to_string(), params: serde_json::json!({ "rows": matrix_to_json(m) }) }
}

/// Name → recipe lookup used by the verifier.
pub struct RecipeRegistry {
    recipes: BTreeMap<String, Box<dyn MatrixRecipe>>,
}

impl Default for RecipeRegistry {
    fn default() -> Self {
        Self::new()
    }
}

impl std::fmt::Debug for RecipeRegistry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.recipes.keys()).finish()
    }
}

impl RecipeRegistry {
    /// A registry holding only the built-in recipes (`"explicit"`).
    pub fn new() -> Self {
        let mut r = Self { recipes: BTreeMap::new() };
        r.register(Box::new(ExplicitRecipe)).expect("empty registry has no duplicates");
        r
    }

    /// Adds a recipe; fails if its name is already taken.
    pub fn register(&mut self, recipe: Box<dyn MatrixRecipe>) -> Result<(), CertError> {
        let name = recipe.name().to_string();
        if self.recipes.contains_key(&name) {
            return Err(CertError::DuplicateRecipe(name));
        }
        self.recipes.insert(name, recipe);
        Ok(())
    }

    /// Registered names, sorted.
    pub fn names(&self) -> Vec<&str> {
        self.recipes.keys().map(String::as_str).collect()
    }

    /// Rebuilds the matrix a certificate refers to.
    pub fn build(&self, r: &RecipeRef) -> Result<RationalMatrix, CertError> {
        let recipe = self.recipes.get(&r.name).ok_or_else(|| CertError::UnknownRecipe(r.name.clone()))?;
        recipe.build(&r.params).map_err(|message| CertError::Recipe { name: r.name.clone(), message })
    }
}
