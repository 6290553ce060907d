/* Four threads orienting different meshes at once give exactly the results of one
 * thread, statuses and messages included (each thread has its own last error). */
#include <pthread.h>

#include "check.h"

#define JOBS 4

typedef struct {
    SherdMesh *mesh;
    SherdStatus status;
    SherdAxis axis;
    char message[512];
} Job;

static void *orient(void *argument) {
    Job *job = (Job *)argument;
    memset(&job->axis, 0, sizeof job->axis);
    job->axis.size = sizeof job->axis;
    job->status = sherd_orient_automatic(job->mesh, NULL, &job->axis, NULL, NULL);
    job->message[0] = '\0';
    if (job->status != SHERD_STATUS_OK) {
        strncpy(job->message, sherd_last_error_message(), sizeof job->message - 1);
        job->message[sizeof job->message - 1] = '\0';
    }
    return NULL;
}

int main(void) {
    /* Different kinds, so that some are refused with a message and some are not. */
    const uint32_t kinds[JOBS] = {SHERD_SYNTH_KIND_RIM, SHERD_SYNTH_KIND_FLAT_BASE, SHERD_SYNTH_KIND_BASE,
                                  SHERD_SYNTH_KIND_NEAR_SPHERICAL};
    Job alone[JOBS], together[JOBS];
    pthread_t threads[JOBS];
    int i;

    for (i = 0; i < JOBS; ++i) {
        memset(&alone[i], 0, sizeof alone[i]);
        CHECK_OK(sherd_synthetic_sherd((uint64_t)(i + 1), kinds[i], 4000, 0.02, &alone[i].mesh, NULL, NULL));
        together[i] = alone[i];
        orient(&alone[i]);
    }
    for (i = 0; i < JOBS; ++i) CHECK(pthread_create(&threads[i], NULL, orient, &together[i]) == 0);
    for (i = 0; i < JOBS; ++i) CHECK(pthread_join(threads[i], NULL) == 0);
    for (i = 0; i < JOBS; ++i) {
        CHECK(together[i].status == alone[i].status);
        CHECK(memcmp(&together[i].axis, &alone[i].axis, sizeof(SherdAxis)) == 0);
        CHECK(strcmp(together[i].message, alone[i].message) == 0);
        printf("  job %d: %s %s\n", i, sherd_status_name(alone[i].status), alone[i].message);
        sherd_mesh_free(alone[i].mesh);
    }
    printf("test_threads: ok\n");
    return 0;
}
