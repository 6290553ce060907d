/* The names of the C ABI's named values, listed and parsed by the library
 * (sherd_vocabulary_*): every vocabulary lists its values once each, the listed value is
 * the header's constant, a name parses back to its value, and a bad vocabulary, index,
 * name or size is refused with a message naming it. */
#include "check.h"

/* The entry `index` of `vocabulary`, checked. */
static SherdVocabularyEntry entry_of(uint32_t vocabulary, size_t index) {
    SherdVocabularyEntry entry;
    memset(&entry, 0, sizeof entry);
    entry.size = sizeof entry;
    CHECK_OK(sherd_vocabulary_entry(vocabulary, index, &entry));
    CHECK(entry.size == sizeof entry);
    CHECK(entry.name != NULL && strlen(entry.name) > 0);
    CHECK(entry.description != NULL && strlen(entry.description) > 0);
    return entry;
}

/* The value `name` stands for in `vocabulary`. */
static uint32_t value_named(uint32_t vocabulary, const char *name) {
    uint32_t value = 12345u;
    CHECK_OK(sherd_vocabulary_value(vocabulary, name, &value));
    return value;
}

static void test_every_vocabulary_lists_distinct_names_that_parse_back(void) {
    uint32_t vocabulary;
    for (vocabulary = SHERD_VOCABULARY_CRITERION; vocabulary <= SHERD_VOCABULARY_RECORD_STATUS; ++vocabulary) {
        size_t count = 0, i, j;
        CHECK_OK(sherd_vocabulary_count(vocabulary, &count));
        CHECK(count >= 2);
        for (i = 0; i < count; ++i) {
            SherdVocabularyEntry entry = entry_of(vocabulary, i);
            CHECK(value_named(vocabulary, entry.name) == entry.value);
            for (j = 0; j < i; ++j) {
                SherdVocabularyEntry other = entry_of(vocabulary, j);
                CHECK(strcmp(other.name, entry.name) != 0);
                CHECK(other.value != entry.value);
            }
        }
    }
}

static void test_names_are_the_constants(void) {
    size_t count = 0, i;
    int seen_auto = 0;
    CHECK_OK(sherd_vocabulary_count(SHERD_VOCABULARY_CRITERION, &count));
    CHECK(count == 5);
    for (i = 0; i < count; ++i) {
        SherdVocabularyEntry entry = entry_of(SHERD_VOCABULARY_CRITERION, i);
        if (strcmp(entry.name, "auto") == 0) {
            CHECK(entry.value == SHERD_CRITERION_AUTO);
            seen_auto = 1;
        }
    }
    CHECK(seen_auto);
    CHECK(value_named(SHERD_VOCABULARY_CRITERION, "circles") == SHERD_CRITERION_CIRCLES);
    CHECK(value_named(SHERD_VOCABULARY_PARETO_CHOICE, "mean_of_best") == SHERD_PARETO_CHOICE_MEAN_OF_BEST);
    /* Case, hyphens and aliases as people type them. */
    CHECK(value_named(SHERD_VOCABULARY_PLACEMENT, "True-Distance") == SHERD_PLACEMENT_TRUE_DISTANCE);
    CHECK(value_named(SHERD_VOCABULARY_STYLE, "color") == SHERD_STYLE_COLOUR);
    CHECK(value_named(SHERD_VOCABULARY_FORMAT, "ps") == SHERD_FORMAT_EPS);
    CHECK(value_named(SHERD_VOCABULARY_RECORD_STATUS, "axis_uncertain") == SHERD_RECORD_STATUS_AXIS_UNCERTAIN);
    /* Bit vocabularies list their bits. */
    CHECK(value_named(SHERD_VOCABULARY_ANNOTATION, "wall_thickness") == SHERD_ANNOTATION_WALL_THICKNESS);
}

static void test_bad_arguments_are_refused_with_a_message(void) {
    size_t count = 77;
    uint32_t value = 77;
    SherdVocabularyEntry entry;
    memset(&entry, 0, sizeof entry);
    entry.size = sizeof entry;

    CHECK_STATUS(sherd_vocabulary_count(99u, &count), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("`vocabulary` 99 is not a SHERD_VOCABULARY_* value (0 to 12)");
    CHECK(count == 77);
    CHECK_STATUS(sherd_vocabulary_entry(99u, 0, &entry), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("SHERD_VOCABULARY_*");

    CHECK_OK(sherd_vocabulary_count(SHERD_VOCABULARY_SURFACE, &count));
    CHECK_STATUS(sherd_vocabulary_entry(SHERD_VOCABULARY_SURFACE, count, &entry), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("`index` 3 is past the 3 values");
    CHECK(entry.name == NULL);

    entry.size = 4;
    CHECK_STATUS(sherd_vocabulary_entry(SHERD_VOCABULARY_SURFACE, 0, &entry), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("sizeof(SherdVocabularyEntry)");
    CHECK_STATUS(sherd_vocabulary_entry(SHERD_VOCABULARY_SURFACE, 0, NULL), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_vocabulary_count(SHERD_VOCABULARY_SURFACE, NULL), SHERD_STATUS_NULL_POINTER);

    CHECK_STATUS(sherd_vocabulary_value(SHERD_VOCABULARY_CRITERION, "bogus", &value), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("unknown criterion \"bogus\"; the criteria are auto, circles, pareto, profile, tangent");
    CHECK(value == 77);
    CHECK_STATUS(sherd_vocabulary_value(SHERD_VOCABULARY_CRITERION, NULL, &value), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_vocabulary_value(SHERD_VOCABULARY_CRITERION, "auto", NULL), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_vocabulary_value(SHERD_VOCABULARY_CRITERION, "\xff", &value), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("not UTF-8");
}

int main(void) {
    test_every_vocabulary_lists_distinct_names_that_parse_back();
    test_names_are_the_constants();
    test_bad_arguments_are_refused_with_a_message();
    printf("test_vocabulary: ok\n");
    return 0;
}
